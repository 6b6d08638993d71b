#!/usr/bin/env python3
"""The scale measurement of the building floor (scenes/building-floor.gltf, 103k polygons):
solve time and peak memory, the energy balance, and each room's accuracy against the same
room solved alone (a floor of one room per side, built by the same generator: the room's
geometry is the same, only its neighbours are missing).

    python3 bench/scale/building_floor.py [--cli build/app/radiosity-cli] [--rooms s00 s15 n07]

Prints one line per measure; exits 1 when a solve fails. Run on demand (minutes), not in
./test.sh."""
import argparse, json, os, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, 'scenes'))
import generate  # noqa: E402


def luminance(c):
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]


def solve(cli, scene, report, extra=()):
    start = time.monotonic()
    r = subprocess.run(['/usr/bin/time', '-f', '%M', cli, 'solve', scene, '--report', report, '--force', *extra],
                       capture_output=True, text=True)
    seconds = time.monotonic() - start
    if r.returncode != 0:
        sys.exit('%s: solve failed (exit %d): %s' % (scene, r.returncode, r.stderr.strip().splitlines()[-1:]))
    peak_kib = int(r.stderr.strip().splitlines()[-1])
    with open(report) as f:
        return json.load(f), seconds, peak_kib * 1024


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--cli', default=os.path.join(ROOT, 'build', 'app', 'radiosity-cli'))
    ap.add_argument('--rooms', nargs='*', default=['s00', 's15', 'n07', 'n29'])
    ap.add_argument('--floor-args', default='', help='more solve options for the whole floor, e.g. "--min-area 0.003"')
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        alone = os.path.join(tmp, 'one-room-per-side.gltf')
        with open(alone, 'wb') as f:
            f.write(generate.build_gltf(generate.building_floor(1)))
        floor, seconds, peak = solve(args.cli, os.path.join(ROOT, 'scenes', 'building-floor.gltf'),
                                     os.path.join(tmp, 'floor.json'), args.floor_args.split())
        e = floor['energy']
        print('building-floor: %d polygons, %d links, %d p-links, solve %.1f s (wall %.1f s), peak memory %.2f GB, '
              'engine memory %.2f GB, converged %s, threshold scale %g' % (
                  floor['polygons'], floor['links'], floor['passive_links'], floor['seconds']['total'], seconds,
                  peak / 1e9, floor['memory_bytes']['total'] / 1e9, floor['converged'], floor['threshold_scale']))
        print('building-floor energy: lost %.2f%%, escaped %.2f%%, back faces %.2f%% of the emitted power' % (
            100 * e['lost'] / e['emitted'], 100 * e['escaped'] / e['emitted'], 100 * e['back_faces'] / e['emitted']))
        single, _, _ = solve(args.cli, alone, os.path.join(tmp, 'alone.json'))
        # The near-side rooms against the alone floor's s00, the far-side (turned) ones against its n00.
        refs = {}
        for side in 'sn':
            refs[side] = {o['name'][len('room-%s00-' % side):]: o for o in single['objects']
                          if o['name'].startswith('room-%s00-' % side)}
        refs['s']['chair'] = next(o for o in single['objects'] if o['name'] == 'chair')
        for room in args.rooms:
            ref = refs[room[0]]
            worst, worst_name, errors = 0.0, '', []
            for o in floor['objects']:
                name = o['name']
                if name == 'chair' and room == 's00':
                    part = 'chair'
                elif name.startswith('room-%s-' % room):
                    part = name[len('room-%s-' % room):]
                else:
                    continue
                b = luminance(ref[part]['radiosity'])
                if b <= 0.0:
                    continue
                err = abs(luminance(o['radiosity']) - b) / b
                errors.append(err)
                if err > worst:
                    worst, worst_name = err, part
            errors.sort()
            print('room %s vs the room alone: median object error %.2f%%, worst %.2f%% (%s), %d objects' % (
                room, 100 * errors[len(errors) // 2], 100 * worst, worst_name, len(errors)))


if __name__ == '__main__':
    main()
