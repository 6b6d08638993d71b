#!/usr/bin/env python3
"""Block-RMS difference between an image and a Cycles reference (standard library only).

    python3 bench/cycles/compare.py IMAGE.pfm REFERENCE.pfm REFERENCE-lights.pfm [--exclude X0,Y0,X1,Y1]

REFERENCE-lights.pfm may be "-": no pixel sees a light. --exclude leaves out the pixels with
X0 <= x < X1 and Y0 <= y < Y1 (rows from the top) as light pixels are, for a comparison between
two of our own images where one small region (a lamp's hot spot) would say nothing but how each
was meshed.

The same metric as tests/support/ImageCompare.cpp (keep the two in step):
- luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709, linear);
- pixels the reference's light mask marks, and their 8 neighbours, are left out (a light
  edge that falls half a pixel differently is not a radiosity error);
- the image is cut into 8x8 blocks; a block keeps the mean of its remaining pixels, and a
  block with fewer than half of its pixels remaining (mostly light) is left out;
- block_rms = sqrt(mean over blocks of (ours - reference)^2) / (reference mean over the
  remaining pixels of those blocks); mean_ratio = ours mean / reference mean, same pixels.
Prints one JSON line. Used to measure the seed-to-seed noise of the references.
"""

import json
import struct
import sys

BLOCK = 8


def read_pfm(path):
    """Luminance, rows top to bottom (PFM stores them bottom to top)."""
    with open(path, 'rb') as f:
        data = f.read()
    parts = data.split(b'\n', 3)
    if parts[0].strip() != b'PF':
        raise SystemExit('%s: not an RGB PFM' % path)
    w, h = (int(v) for v in parts[1].split())
    little = float(parts[2]) < 0
    vals = struct.unpack(('<' if little else '>') + '%df' % (w * h * 3), parts[3][:w * h * 12])
    rows = []
    for y in range(h - 1, -1, -1):
        base = 3 * w * y
        rows.append([0.2126 * vals[base + 3 * x] + 0.7152 * vals[base + 3 * x + 1] + 0.0722 * vals[base + 3 * x + 2]
                     for x in range(w)])
    return w, h, rows


def block_rms(ours, reference, lights, exclude=None):
    w, h, a = ours
    w2, h2, b = reference
    w3, h3, m = lights if lights is not None else (w, h, [[0.0] * w for _ in range(h)])
    if (w, h) != (w2, h2) or (w, h) != (w3, h3):
        raise SystemExit('image sizes differ')
    keep = [[all(not (m[yy][xx] > 0.0) for yy in range(max(0, y - 1), min(h, y + 2))
                 for xx in range(max(0, x - 1), min(w, x + 2))) for x in range(w)] for y in range(h)]
    if exclude:
        x0, y0, x1, y1 = exclude
        for y in range(max(0, y0), min(h, y1)):
            for x in range(max(0, x0), min(w, x1)):
                keep[y][x] = False
    sq, blocks, sum_a, sum_b, n = 0.0, 0, 0.0, 0.0, 0
    for by in range(0, h, BLOCK):
        for bx in range(0, w, BLOCK):
            pix = [(y, x) for y in range(by, min(h, by + BLOCK)) for x in range(bx, min(w, bx + BLOCK)) if keep[y][x]]
            total = (min(h, by + BLOCK) - by) * (min(w, bx + BLOCK) - bx)
            if 2 * len(pix) < total:
                continue
            ba = sum(a[y][x] for y, x in pix)
            bb = sum(b[y][x] for y, x in pix)
            sq += ((ba - bb) / len(pix)) ** 2
            blocks += 1
            sum_a += ba
            sum_b += bb
            n += len(pix)
    mean_b = sum_b / n
    return {'block_rms': (sq / blocks) ** 0.5 / mean_b, 'mean_ratio': sum_a / sum_b, 'blocks': blocks,
            'pixels': n, 'reference_mean': mean_b}


def main():
    args = sys.argv[1:]
    exclude = None
    if len(args) == 5 and args[3] == '--exclude':
        try:
            exclude = [int(v) for v in args[4].split(',')]
        except ValueError:
            exclude = []
        if len(exclude) != 4:
            raise SystemExit('--exclude: expected X0,Y0,X1,Y1 (four integers), got ' + args[4])
        args = args[:3]
    if len(args) != 3:
        raise SystemExit(__doc__)
    lights = None if args[2] == '-' else read_pfm(args[2])
    print(json.dumps(block_rms(read_pfm(args[0]), read_pfm(args[1]), lights, exclude)))


if __name__ == '__main__':
    main()
