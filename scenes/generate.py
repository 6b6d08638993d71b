#!/usr/bin/env python3
"""Generate the shipped test scenes as self-contained glTF 2.0 files.

Conventions (see ../../shared/DESIGN.md, "Scenes"): Y up, metres,
counter-clockwise winding is the front face, one named node with one mesh per
object, all geometry baked in world space (nodes carry no transform except the
camera), reflectance in pbrMetallicRoughness.baseColorFactor, emission in
emissiveFactor (times KHR_materials_emissive_strength when > 1), dynamic-object
candidates marked with node extras {"dynamic": true}. Rectangles are written as
two triangles (a, b, c), (a, c, d) sharing the diagonal a-c, so an importer
merges them back into one quad.

NOTE on the door of dark-room.gltf: the door is hinged on the vertical edge of
its bounding box at its low-x, corridor-side corner (node extras "hinge" gives
the point and axis). Rotations given on the CLI are about the object's
BOUNDING-BOX CENTRE, not about the hinge, so to open the door like a door you
must combine the rotation with a translation (or rotate about the hinge point
in code): rotating by angle a about the hinge equals rotating by a about the
bbox centre c and then translating by (R(a) - I)(c - hinge).

Usage: python3 scenes/generate.py [--out DIR] [--check] [--only NAME ...]
Only the Python standard library is used; output is byte-identical on every run.
"""

import argparse
import base64
import json
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# ---------------------------------------------------------------------------
# Small vector helpers (tuples of floats)


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return (a[0] / n, a[1] / n, a[2] / n)


def newell(poly):
    """Area-weighted normal (length = 2 * area)."""
    nx = ny = nz = 0.0
    for i in range(len(poly)):
        a = poly[i]
        b = poly[(i + 1) % len(poly)]
        nx += (a[1] - b[1]) * (a[2] + b[2])
        ny += (a[2] - b[2]) * (a[0] + b[0])
        nz += (a[0] - b[0]) * (a[1] + b[1])
    return (nx, ny, nz)


def centroid(poly):
    n = len(poly)
    return (sum(p[0] for p in poly) / n, sum(p[1] for p in poly) / n, sum(p[2] for p in poly) / n)


def facing(poly, ref, outward=True):
    """Return poly wound so its normal points away from (outward) or toward ref."""
    n = newell(poly)
    d = dot(n, sub(centroid(poly), ref))
    if (d < 0) == outward:
        return list(reversed(poly))
    return list(poly)


class Rng:
    """Tiny deterministic 64-bit LCG (independent of Python's random module)."""

    def __init__(self, seed):
        self.s = (seed * 6364136223846793005 + 1442695040888963407) & 0xFFFFFFFFFFFFFFFF

    def random(self):
        self.s = (self.s * 6364136223846793005 + 1442695040888963407) & 0xFFFFFFFFFFFFFFFF
        return (self.s >> 11) / float(1 << 53)

    def uniform(self, a, b):
        return a + (b - a) * self.random()


# ---------------------------------------------------------------------------
# Transforms: 3x4 matrices as ((r00, r01, r02, t0), (r10, ...), (r20, ...))


def m_translate(t):
    return ((1.0, 0.0, 0.0, t[0]), (0.0, 1.0, 0.0, t[1]), (0.0, 0.0, 1.0, t[2]))


def m_rot(axis, angle):
    c, s = math.cos(angle), math.sin(angle)
    if axis == 'x':
        return ((1.0, 0.0, 0.0, 0.0), (0.0, c, -s, 0.0), (0.0, s, c, 0.0))
    if axis == 'y':
        return ((c, 0.0, s, 0.0), (0.0, 1.0, 0.0, 0.0), (-s, 0.0, c, 0.0))
    return ((c, -s, 0.0, 0.0), (s, c, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0))


def m_mul(a, b):
    """a @ b (apply b first)."""
    r = []
    for i in range(3):
        row = []
        for j in range(4):
            v = sum(a[i][k] * b[k][j] for k in range(3))
            if j == 3:
                v += a[i][3]
            row.append(v)
        r.append(tuple(row))
    return tuple(r)


def m_chain(*ms):
    """m_chain(A, B, C) applies A first, then B, then C."""
    r = ms[0]
    for m in ms[1:]:
        r = m_mul(m, r)
    return r


def m_apply(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))


def xform(polys, m):
    # rotations and translations only: winding is preserved
    return [[m_apply(m, p) for p in poly] for poly in polys]


# ---------------------------------------------------------------------------
# Primitive builders: each returns a list of polygons wound outward


def box(x0, y0, z0, x1, y1, z1, skip=()):
    """Axis-aligned box; skip any of 'bottom','top','left'(-x),'right'(+x),'back'(-z),'front'(+z)."""
    c = ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2)
    faces = {
        'bottom': [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
        'top': [(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)],
        'left': [(x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (x0, y0, z1)],
        'right': [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
        'back': [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)],
        'front': [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
    }
    out = []
    for k in ('bottom', 'top', 'left', 'right', 'back', 'front'):
        if k not in skip:
            out.append(facing(faces[k], c))
    return out


def cap_split(pts):
    """Split a convex planar polygon (ordered) into fan quads (+ one triangle)."""
    out = []
    i = 1
    n = len(pts)
    while i + 2 < n:
        out.append([pts[0], pts[i], pts[i + 1], pts[i + 2]])
        i += 2
    if i + 1 < n:
        out.append([pts[0], pts[i], pts[i + 1]])
    return out


def prism_y(outline, y0, y1, top=True, bottom=True):
    """Vertical extrusion of a convex outline given as [(x, z), ...]."""
    cx = sum(p[0] for p in outline) / len(outline)
    cz = sum(p[1] for p in outline) / len(outline)
    c = (cx, (y0 + y1) / 2, cz)
    out = []
    n = len(outline)
    for i in range(n):
        a, b = outline[i], outline[(i + 1) % n]
        out.append(facing([(a[0], y0, a[1]), (b[0], y0, b[1]), (b[0], y1, b[1]), (a[0], y1, a[1])], c))
    if top:
        out += [facing(q, c) for q in cap_split([(p[0], y1, p[1]) for p in outline])]
    if bottom:
        out += [facing(q, c) for q in cap_split([(p[0], y0, p[1]) for p in outline])]
    return out


def circle(cx, cz, r, n, phase=0.0):
    return [(cx + r * math.cos(phase + 2 * math.pi * i / n), cz + r * math.sin(phase + 2 * math.pi * i / n))
            for i in range(n)]


def cylinder_y(cx, cz, r, y0, y1, n, top=True, bottom=True, phase=0.0):
    return prism_y(circle(cx, cz, r, n, phase), y0, y1, top, bottom)


def rrect_layer(hw, hd, r, m, k):
    """Rounded-rectangle outline (half sizes hw, hd, corner radius r, m segments per
    corner, k segments per straight edge), counter-clockwise in (x, z)."""
    pts = []
    corners = [(hw - r, hd - r, 0.0), (-(hw - r), hd - r, 0.5 * math.pi),
               (-(hw - r), -(hd - r), math.pi), (hw - r, -(hd - r), 1.5 * math.pi)]
    for ci, (cx, cz, a0) in enumerate(corners):
        for j in range(m + 1):
            a = a0 + 0.5 * math.pi * j / m
            pts.append((cx + r * math.cos(a), cz + r * math.sin(a)))
        # straight edge to next corner
        nx, nz, na = corners[(ci + 1) % 4]
        ex, ez = (cx + r * math.cos(a0 + 0.5 * math.pi), cz + r * math.sin(a0 + 0.5 * math.pi))
        fx, fz = (nx + r * math.cos(na), nz + r * math.sin(na))
        for j in range(1, k):
            t = j / k
            pts.append((ex + (fx - ex) * t, ez + (fz - ez) * t))
    return pts


def rrect_cap(hw, hd, r, m, k, y):
    """Cap of a rounded rectangle split into a grid, edge strips and corner sectors."""
    ix, iz = hw - r, hd - r
    out = []
    xs = [-ix + 2 * ix * i / k for i in range(k + 1)]
    zs = [-iz + 2 * iz * i / k for i in range(k + 1)]
    for i in range(k):
        for j in range(k):
            out.append([(xs[i], y, zs[j]), (xs[i + 1], y, zs[j]), (xs[i + 1], y, zs[j + 1]), (xs[i], y, zs[j + 1])])
    for i in range(k):  # strips
        out.append([(xs[i], y, iz), (xs[i + 1], y, iz), (xs[i + 1], y, hd), (xs[i], y, hd)])
        out.append([(xs[i], y, -iz), (xs[i + 1], y, -iz), (xs[i + 1], y, -hd), (xs[i], y, -hd)])
        out.append([(ix, y, zs[i]), (ix, y, zs[i + 1]), (hw, y, zs[i + 1]), (hw, y, zs[i])])
        out.append([(-ix, y, zs[i]), (-ix, y, zs[i + 1]), (-hw, y, zs[i + 1]), (-hw, y, zs[i])])
    for (cx, cz, a0) in [(ix, iz, 0.0), (-ix, iz, 0.5 * math.pi), (-ix, -iz, math.pi), (ix, -iz, 1.5 * math.pi)]:
        arc = [(cx + r * math.cos(a0 + 0.5 * math.pi * j / m), y, cz + r * math.sin(a0 + 0.5 * math.pi * j / m))
               for j in range(m + 1)]
        out += cap_split([(cx, y, cz)] + arc)
    return out


def cushion(hw, hd, r, m, k, layers, top=True, bottom=True):
    """Rounded slab centred on the y axis: layers = [(y, inset), ...] bottom to top."""
    rings = []
    for (y, d) in layers:
        rings.append([(p[0], y, p[1]) for p in rrect_layer(hw - d, hd - d, r - d, m, k)])
    ymid = (layers[0][0] + layers[-1][0]) / 2
    c = (0.0, ymid, 0.0)
    out = []
    for a, b in zip(rings, rings[1:]):
        n = len(a)
        for i in range(n):
            out.append(facing([a[i], a[(i + 1) % n], b[(i + 1) % n], b[i]], c))
    if top:
        y, d = layers[-1]
        out += [facing(q, c) for q in rrect_cap(hw - d, hd - d, r - d, m, k, y)]
    if bottom:
        y, d = layers[0]
        out += [facing(q, c) for q in rrect_cap(hw - d, hd - d, r - d, m, k, y)]
    return out


# ---------------------------------------------------------------------------
# Scene model


class Obj:
    def __init__(self, name, dynamic=False, extras=None):
        self.name = name
        self.dynamic = dynamic
        self.extras = extras
        self.parts = []  # [(material, [poly, ...])]

    def add(self, material, polys):
        for mat, ps in self.parts:
            if mat == material:
                ps.extend(polys)
                return self
        self.parts.append((material, list(polys)))
        return self

    def count(self):
        return sum(len(ps) for _, ps in self.parts)


class SceneBuilder:
    def __init__(self, name):
        self.name = name
        self.materials = {}  # name -> (rgb, emissive_rgb or None, strength)
        self.objects = []
        self.camera = None
        self.rooms = []  # (object name, interior reference point) for --check
        self.outward = []  # (object name, part centre) for closed parts checked outward
        self.lights = []  # KHR_lights_punctual: dicts (name, type, color, intensity, position, [aim, cones])
        self.textures = {}  # material name -> (width, height, texels (rows from the top, sRGB bytes), metres a repeat)

    def material(self, name, rgb, emission=None):
        """emission: (r, g, b) radiometric emission E; split into factor * strength."""
        assert all(0.0 <= c < 1.0 for c in rgb), name
        self.materials[name] = (rgb, emission)
        return name

    def texture(self, material, width, height, texels, repeat):
        """A base colour texture for `material` (whose rgb is then the baseColorFactor): texels
        are (r, g, b) sRGB bytes, rows from the top; laid on every polygon by planar projection
        along its normal's largest axis, one repeat every `repeat` metres."""
        assert len(texels) == width * height, material
        self.textures[material] = (width, height, texels, repeat)
        return material

    def obj(self, name, dynamic=False, extras=None):
        assert all(o.name != name for o in self.objects), name
        o = Obj(name, dynamic, extras)
        self.objects.append(o)
        return o

    def point_light(self, name, position, color, intensity):
        self.lights.append({'name': name, 'type': 'point', 'color': color, 'intensity': intensity,
                            'position': position})

    def spot_light(self, name, position, aim, color, intensity, inner, outer):
        """A spot at `position` pointing at the point `aim`; cone angles in radians."""
        self.lights.append({'name': name, 'type': 'spot', 'color': color, 'intensity': intensity,
                            'position': position, 'aim': aim, 'inner': inner, 'outer': outer})

    def set_camera(self, eye, target, yfov, aspect, up=(0.0, 1.0, 0.0)):
        self.camera = (eye, target, up, yfov, aspect)

    def polygon_count(self):
        return sum(o.count() for o in self.objects)


def look_at_quaternion(eye, target, up):
    f = normalize(sub(target, eye))
    z = mul(f, -1.0)
    x = normalize(cross(up, z))
    y = cross(z, x)
    # rotation matrix with columns x, y, z
    m00, m01, m02 = x[0], y[0], z[0]
    m10, m11, m12 = x[1], y[1], z[1]
    m20, m21, m22 = x[2], y[2], z[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    n = math.sqrt(sum(c * c for c in q))
    q = tuple(round(c / n, 9) + 0.0 for c in q)
    return list(q)


def f32(v):
    return struct.unpack('<f', struct.pack('<f', v))[0]


def validate_polygon(poly, where, magnitude=0.0):
    # magnitude: the largest coordinate in the scene; float32 rounds a vertex by up to
    # 6e-8 of it, which far from the origin (the building floor spans 180 m) bends quads
    # by more than the fixed tolerance.
    assert len(poly) in (3, 4), where
    for p in poly:
        for c in p:
            assert math.isfinite(c), where
    n = newell(poly)
    area = 0.5 * length(n)
    assert area > 1e-7, '%s: degenerate polygon (area %g)' % (where, area)
    nn = normalize(n)
    c = centroid(poly)
    size = max(length(sub(p, c)) for p in poly)
    for p in poly:
        assert abs(dot(sub(p, c), nn)) < 1e-6 + 1e-5 * size + 2.4e-7 * magnitude, '%s: non-planar polygon' % where
    for i in range(len(poly)):
        a, b, cc = poly[i - 1], poly[i], poly[(i + 1) % len(poly)]
        turn = dot(cross(sub(b, a), sub(cc, b)), nn)
        assert turn > 1e-9 * max(1.0, size * size), '%s: non-convex polygon %r' % (where, poly)


def png_bytes(width, height, texels):
    """An 8-bit RGB PNG (deflated with zlib)."""
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
    raw = b''.join(b'\x00' + bytes(c for t in texels[y * width:(y + 1) * width] for c in t) for y in range(height))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def planar_uv(poly, p, repeat):
    """Texture coordinates of point p of poly, in repeats: along x and z on a floor or a
    ceiling, along the wall and downward (images run top to bottom) on a wall."""
    n = newell(poly)
    axis = max(range(3), key=lambda i: abs(n[i]))
    if axis == 1:
        return (p[0] / repeat, p[2] / repeat)
    along = p[2] if axis == 0 else p[0]
    return (along / repeat, -p[1] / repeat)


def build_gltf(sb):
    buf = bytearray()
    views, accessors, meshes, nodes = [], [], [], []
    mat_names = sorted({m for o in sb.objects for m, _ in o.parts}, key=list(sb.materials).index)
    mat_index = {m: i for i, m in enumerate(mat_names)}
    materials = []
    uses_strength = False
    for m in mat_names:
        rgb, em = sb.materials[m]
        md = {'name': m, 'pbrMetallicRoughness': {'baseColorFactor': [rgb[0], rgb[1], rgb[2], 1.0],
                                                   'metallicFactor': 0.0, 'roughnessFactor': 1.0}}
        if em is not None:
            s = max(em)
            md['emissiveFactor'] = [em[0] / s, em[1] / s, em[2] / s]
            if s != 1.0:
                assert s > 1.0
                md['extensions'] = {'KHR_materials_emissive_strength': {'emissiveStrength': s}}
                uses_strength = True
        materials.append(md)
    images, textures = [], []
    for m in mat_names:
        if m in sb.textures:
            w, h, texels, _ = sb.textures[m]
            images.append({'name': m, 'mimeType': 'image/png',
                           'uri': 'data:image/png;base64,' + base64.b64encode(png_bytes(w, h, texels)).decode('ascii')})
            textures.append({'source': len(images) - 1, 'sampler': 0})
            materials[mat_index[m]]['pbrMetallicRoughness']['baseColorTexture'] = {'index': len(textures) - 1}

    def align():
        while len(buf) % 4:
            buf.append(0)

    for o in sb.objects:
        prims = []
        for mat, polys in o.parts:
            verts, vindex, idx, uvs = [], {}, [], []
            repeat = sb.textures[mat][3] if mat in sb.textures else None
            for pi, poly in enumerate(polys):
                validate_polygon(poly, '%s/%s #%d' % (sb.name, o.name, pi))
                ids = []
                for p in poly:
                    key = (f32(p[0]), f32(p[1]), f32(p[2]))
                    uv = tuple(f32(c) for c in planar_uv(poly, p, repeat)) if repeat else None
                    if (key, uv) not in vindex:
                        vindex[(key, uv)] = len(verts)
                        verts.append(key)
                        uvs.append(uv)
                    ids.append(vindex[(key, uv)])
                assert len(set(ids)) == len(ids), '%s/%s: vertices merged by float32' % (sb.name, o.name)
                idx += ids[:3]
                if len(ids) == 4:
                    idx += [ids[0], ids[2], ids[3]]
            align()
            off = len(buf)
            for v in verts:
                buf += struct.pack('<3f', *v)
            views.append({'buffer': 0, 'byteOffset': off, 'byteLength': len(buf) - off, 'target': 34962})
            mins = [min(v[i] for v in verts) for i in range(3)]
            maxs = [max(v[i] for v in verts) for i in range(3)]
            accessors.append({'bufferView': len(views) - 1, 'componentType': 5126, 'count': len(verts),
                              'type': 'VEC3', 'min': mins, 'max': maxs})
            pos_acc = len(accessors) - 1
            align()
            off = len(buf)
            if len(verts) < 65536:
                buf += struct.pack('<%dH' % len(idx), *idx)
                ct = 5123
            else:
                buf += struct.pack('<%dI' % len(idx), *idx)
                ct = 5125
            views.append({'buffer': 0, 'byteOffset': off, 'byteLength': len(buf) - off, 'target': 34963})
            accessors.append({'bufferView': len(views) - 1, 'componentType': ct, 'count': len(idx), 'type': 'SCALAR'})
            attributes = {'POSITION': pos_acc}
            if repeat:
                align()
                off = len(buf)
                for uv in uvs:
                    buf += struct.pack('<2f', *uv)
                views.append({'buffer': 0, 'byteOffset': off, 'byteLength': len(buf) - off, 'target': 34962})
                accessors.append({'bufferView': len(views) - 1, 'componentType': 5126, 'count': len(uvs), 'type': 'VEC2'})
                attributes['TEXCOORD_0'] = len(accessors) - 1
            prims.append({'attributes': attributes, 'indices': len(accessors) - 2 if repeat else len(accessors) - 1,
                          'material': mat_index[mat], 'mode': 4})
        meshes.append({'name': o.name, 'primitives': prims})
        node = {'name': o.name, 'mesh': len(meshes) - 1}
        extras = {}
        if o.dynamic:
            extras['dynamic'] = True
        if o.extras:
            extras.update(o.extras)
        if extras:
            node['extras'] = extras
        nodes.append(node)
    align()
    gl = {'asset': {'version': '2.0', 'generator': 'scenes/generate.py'}}
    if uses_strength:
        gl['extensionsUsed'] = ['KHR_materials_emissive_strength']
    cams = []
    if sb.camera:
        eye, target, up, yfov, aspect = sb.camera
        cams.append({'name': 'camera', 'type': 'perspective',
                     'perspective': {'yfov': yfov, 'aspectRatio': aspect, 'znear': 0.01, 'zfar': 100.0}})
        nodes.append({'name': 'camera', 'camera': 0, 'translation': list(eye),
                      'rotation': look_at_quaternion(eye, target, up)})
    if sb.lights:
        # KHR_lights_punctual: a light per node, a spot's node turned so that its -Z points at its aim
        defs = []
        for i, l in enumerate(sb.lights):
            d = {'name': l['name'], 'type': l['type'], 'color': list(l['color']), 'intensity': l['intensity']}
            node = {'name': l['name'], 'translation': list(l['position']),
                    'extensions': {'KHR_lights_punctual': {'light': i}}}
            if l['type'] == 'spot':
                d['spot'] = {'innerConeAngle': l['inner'], 'outerConeAngle': l['outer']}
                aim = normalize(sub(l['aim'], l['position']))
                up = (0.0, 0.0, -1.0) if abs(aim[1]) > 0.9 else (0.0, 1.0, 0.0)
                node['rotation'] = look_at_quaternion(l['position'], l['aim'], up)
            defs.append(d)
            nodes.append(node)
        gl.setdefault('extensionsUsed', []).append('KHR_lights_punctual')
        gl['extensions'] = {'KHR_lights_punctual': {'lights': defs}}
    gl['scene'] = 0
    gl['scenes'] = [{'name': sb.name, 'nodes': list(range(len(nodes)))}]
    gl['nodes'] = nodes
    gl['meshes'] = meshes
    if cams:
        gl['cameras'] = cams
    gl['materials'] = materials
    if textures:
        gl['images'] = images
        gl['textures'] = textures
        gl['samplers'] = [{'magFilter': 9729, 'minFilter': 9729, 'wrapS': 10497, 'wrapT': 10497}]
    gl['accessors'] = accessors
    gl['bufferViews'] = views
    gl['buffers'] = [{'byteLength': len(buf),
                      'uri': 'data:application/octet-stream;base64,' + base64.b64encode(bytes(buf)).decode('ascii')}]
    return (json.dumps(gl, indent=1) + '\n').encode('utf-8')


# ---------------------------------------------------------------------------
# Rooms


def split_points(a0, a1, step, edges):
    """Breakpoints from a0 to a1: a regular grid of about `step`, plus hole edges
    (grid lines too close to an edge are dropped)."""
    n = max(1, int(round((a1 - a0) / step)))
    st = (a1 - a0) / n
    grid = [a0 + st * i for i in range(n + 1)]
    edges = sorted(e for e in set(edges) if a0 < e < a1)
    pts = [g for g in grid if all(abs(g - e) > 0.35 * st for e in edges) or g in (a0, a1)]
    pts = sorted(set(pts + edges))
    return pts


def tiled_plane(axis, const, ar, br, step, holes, ref, inward=True):
    """Tiles on the plane coord[axis] = const; (a, b) are the other two coordinates in
    increasing axis order; holes = [(a0, a1, b0, b1)]; faces oriented toward ref."""
    oa, ob = [i for i in range(3) if i != axis]
    apts = split_points(ar[0], ar[1], step, [h[0] for h in holes] + [h[1] for h in holes])
    bpts = split_points(br[0], br[1], step, [h[2] for h in holes] + [h[3] for h in holes])

    def P(a, b):
        p = [0.0, 0.0, 0.0]
        p[axis], p[oa], p[ob] = const, a, b
        return tuple(p)

    out = []
    for i in range(len(apts) - 1):
        for j in range(len(bpts) - 1):
            ca, cb = (apts[i] + apts[i + 1]) / 2, (bpts[j] + bpts[j + 1]) / 2
            if any(h[0] < ca < h[1] and h[2] < cb < h[3] for h in holes):
                continue
            q = [P(apts[i], bpts[j]), P(apts[i + 1], bpts[j]), P(apts[i + 1], bpts[j + 1]), P(apts[i], bpts[j + 1])]
            out.append(facing(q, ref, outward=not inward))
    return out


def room(sb, prefix, lo, hi, step, mats, holes=None, skip=(), lights=(), light_mat=None, light_names=None):
    """Box room lo..hi, surfaces facing in. holes: {'left'|'right'|'back'|'front': [(a0,a1,b0,b1)]}
    in that wall's (a, b) = (the other two coordinates in x, y, z order). lights: [(x0, x1, z0, z1)]
    rectangles cut out of the ceiling and filled with emitters 0.1 mm below it."""
    holes = holes or {}
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2)
    wall_m, floor_m, ceil_m = mats
    spec = [
        ('floor', 1, y0, (x0, x1), (z0, z1), floor_m, []),
        ('ceiling', 1, y1, (x0, x1), (z0, z1), ceil_m, [(l[0], l[1], l[2], l[3]) for l in lights]),
        ('wall-left', 0, x0, (y0, y1), (z0, z1), wall_m, holes.get('left', [])),
        ('wall-right', 0, x1, (y0, y1), (z0, z1), wall_m, holes.get('right', [])),
        ('wall-back', 2, z0, (x0, x1), (y0, y1), wall_m, holes.get('back', [])),
        ('wall-front', 2, z1, (x0, x1), (y0, y1), wall_m, holes.get('front', [])),
    ]
    for name, axis, const, ar, br, mat, hl in spec:
        if name in skip:
            continue
        full = prefix + name
        sb.obj(full).add(mat, tiled_plane(axis, const, ar, br, step, hl, c))
        sb.rooms.append((full, c))
    for i, l in enumerate(lights):
        nm = light_names[i] if light_names else '%slight-%d' % (prefix, i + 1)
        yl = y1 - 0.0001
        q = [(l[0], yl, l[2]), (l[1], yl, l[2]), (l[1], yl, l[3]), (l[0], yl, l[3])]
        sb.obj(nm).add(light_mat, [facing(q, c, outward=False)])
        sb.rooms.append((nm, c))
    return c


# ---------------------------------------------------------------------------
# Cornell box


def cornell():
    sb = SceneBuilder('cornell-box')
    white = sb.material('white', (0.725, 0.71, 0.68))
    red = sb.material('red', (0.63, 0.065, 0.05))
    green = sb.material('green', (0.14, 0.45, 0.091))
    light = sb.material('light', (0.78, 0.78, 0.78), emission=(17.0, 12.0, 4.0))

    def mm(*pts):
        return [(p[0] / 1000.0, p[1] / 1000.0, p[2] / 1000.0) for p in pts]

    centre = (0.278, 0.2744, 0.2796)
    sb.obj('floor').add(white, [mm((552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2))])
    # ceiling (556,548.8,0) (556,548.8,559.2) (0,548.8,559.2) (0,548.8,0) with the light hole
    # x in [213, 343], z in [227, 332]: four quads around the hole, all facing down
    cy = 548.8
    ceil = []
    for (xa, xb, za, zb) in [(0, 556, 0, 227), (0, 556, 332, 559.2), (343, 556, 227, 332), (0, 213, 227, 332)]:
        ceil.append(facing(mm((xb, cy, za), (xb, cy, zb), (xa, cy, zb), (xa, cy, za)), centre, outward=False))
    sb.obj('ceiling').add(white, ceil)
    sb.obj('light').add(light, [mm((343, cy - 0.1, 227), (343, cy - 0.1, 332), (213, cy - 0.1, 332), (213, cy - 0.1, 227))])
    sb.obj('back-wall').add(white, [mm((549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2))])
    # The published left wall is not planar (its corners are 0.8 mm off any plane), so it is
    # written as two exact triangles (a, b, c), (c, d, a); they are not coplanar (0.47 degrees)
    # and must not be merged into a quad.
    sb.obj('left-wall-red').add(red, [mm((552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2)),
                                      mm((556, 548.8, 559.2), (556, 548.8, 0), (552.8, 0, 0))])
    sb.obj('right-wall-green').add(green, [mm((0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2))])
    for n in ('floor', 'ceiling', 'light', 'back-wall', 'left-wall-red', 'right-wall-green'):
        sb.rooms.append((n, centre))

    def block(name, top, h, dynamic):
        top = mm(*top)
        hm = h / 1000.0
        c = (sum(p[0] for p in top) / 4, hm / 2, sum(p[2] for p in top) / 4)
        polys = [facing(top, c)]
        for i in range(4):
            a, b = top[i], top[(i + 1) % 4]
            polys.append(facing([(a[0], 0.0, a[2]), (b[0], 0.0, b[2]), b, a], c))
        sb.obj(name, dynamic=dynamic).add(white, polys)
        sb.outward.append((name, c))

    block('short-block', [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)], 165, True)
    block('tall-block', [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)], 330, False)
    sb.set_camera((0.278, 0.273, -0.800), (0.278, 0.273, 0.0), 2 * math.atan(0.0125 / 0.035), 1.0)
    return sb


# ---------------------------------------------------------------------------
# Furniture, built in local coordinates (origin on the floor, front toward +z)


def chair_parts():
    """Office swivel chair: 5-star base with casters, gas column, cushioned seat and
    back, two armrests. About 860 polygons. Seat front faces +z."""
    fabric, metal = [], []
    # 5-star base
    for i in range(5):
        a = 0.5 * math.pi + 2 * math.pi * i / 5
        rot = m_rot('y', a)
        metal += xform(box(0.045, 0.07, -0.0225, 0.30, 0.10, 0.0225, skip=('left',)), rot)
        # caster: vertical stem into a wheel lying on its side (axis horizontal)
        stem = cylinder_y(0.28, 0.0, 0.012, 0.055, 0.07, 8, top=False, bottom=False)
        wheel = cylinder_y(0.0, 0.0, 0.03, -0.0125, 0.0125, 12, phase=math.pi / 12)
        wheel = xform(wheel, m_chain(m_rot('x', 0.5 * math.pi), m_translate((0.28, 0.031, 0.0))))
        metal += xform(stem + wheel, rot)
    metal += cylinder_y(0.0, 0.0, 0.05, 0.06, 0.11, 16, phase=math.pi / 16)
    metal += cylinder_y(0.0, 0.0, 0.026, 0.11, 0.25, 16, bottom=False)
    metal += cylinder_y(0.0, 0.0, 0.018, 0.25, 0.40, 16, top=False, bottom=False)
    metal += box(-0.09, 0.40, -0.09, 0.09, 0.45, 0.09, skip=('top',))
    # seat
    seat_layers = [(0.45, 0.02), (0.454, 0.008), (0.462, 0.002), (0.475, 0.0), (0.50, 0.0),
                   (0.51, 0.004), (0.517, 0.013), (0.521, 0.03)]
    fabric += cushion(0.24, 0.23, 0.07, 4, 2, seat_layers)
    # back: a cushion stood up (local thickness y -> world z), centre (0, 0.81, -0.27)
    back_layers = [(-0.03, 0.03), (-0.026, 0.013), (-0.019, 0.004), (-0.01, 0.0), (0.01, 0.0),
                   (0.019, 0.004), (0.026, 0.013), (0.03, 0.03)]
    back = cushion(0.22, 0.25, 0.07, 4, 2, back_layers)
    fabric += xform(back, m_chain(m_rot('x', 0.5 * math.pi), m_translate((0.0, 0.81, -0.27))))
    # back support: horizontal bar from the mechanism, vertical bar behind the back
    metal += box(-0.025, 0.41, -0.335, 0.025, 0.44, -0.09, skip=('front',))
    metal += box(-0.025, 0.44, -0.335, 0.025, 0.75, -0.305, skip=('bottom',))
    # armrests
    for sgn in (1.0, -1.0):
        xa, xb = sorted((sgn * 0.09, sgn * 0.27))
        metal += box(xa, 0.42, -0.02, xb, 0.44, 0.02, skip=('left',) if sgn > 0 else ('right',))
        pa, pb = sorted((sgn * 0.255, sgn * 0.285))
        metal += box(pa, 0.44, -0.02, pb, 0.68, 0.02, skip=('bottom', 'top'))
        pad = cushion(0.035, 0.13, 0.03, 4, 1, [(0.68, 0.0), (0.70, 0.0), (0.708, 0.006), (0.712, 0.02)])
        fabric += xform(pad, m_translate((sgn * 0.27, 0.0, 0.0)))
    return fabric, metal


_CHAIR = None


def add_chair(sb, name, x, z, yaw, mats, dynamic=False):
    global _CHAIR
    if _CHAIR is None:
        _CHAIR = chair_parts()
    m = m_chain(m_rot('y', yaw), m_translate((x, 0.0, z)))
    o = sb.obj(name, dynamic=dynamic)
    o.add(mats['fabric'], xform(_CHAIR[0], m))
    o.add(mats['metal'], xform(_CHAIR[1], m))
    return o


def add_desk(sb, name, x, z, yaw, mats, w=1.6, d=0.8, h=0.74, monitor=True):
    """Desk centred at (x, z); its user sits on the +z side (local)."""
    wood, metal, dark = [], [], []
    hw, hd = w / 2, d / 2
    wood += box(-hw, h - 0.03, -hd, hw, h, hd)
    for sx in (-1, 1):
        for sz in (-1, 1):
            lx = sx * (hw - 0.05)
            lz = sz * (hd - 0.05)
            metal += box(lx - 0.025, 0.0, lz - 0.025, lx + 0.025, h - 0.03, lz + 0.025, skip=('bottom', 'top'))
    # modesty panel between the back legs
    metal += box(-hw + 0.075, 0.30, -hd + 0.04, hw - 0.075, h - 0.03, -hd + 0.06, skip=('top', 'left', 'right'))
    # drawer pedestal on the right
    px0, px1 = hw - 0.52, hw - 0.12
    pz0, pz1 = -hd + 0.1, hd - 0.08
    wood += box(px0, 0.0, pz0, px1, h - 0.03, pz1, skip=('bottom', 'top'))
    for i in range(3):
        y0 = 0.04 + i * 0.22
        wood += box(px0 + 0.01, y0, pz1, px1 - 0.01, y0 + 0.2, pz1 + 0.018, skip=('back',))
        metal += box(px0 + 0.14, y0 + 0.15, pz1 + 0.018, px1 - 0.14, y0 + 0.165, pz1 + 0.035, skip=('back',))
    if monitor:
        dark += box(-0.12, h, -hd + 0.1, 0.12, h + 0.012, -hd + 0.28, skip=('bottom',))
        dark += box(-0.025, h + 0.012, -hd + 0.16, 0.025, h + 0.30, -hd + 0.19, skip=('bottom', 'front'))
        dark += box(-0.30, h + 0.10, -hd + 0.19, 0.30, h + 0.46, -hd + 0.22)
        dark += box(-0.22, h, -0.02, 0.22, h + 0.02, 0.13, skip=('bottom',))  # keyboard
    m = m_chain(m_rot('y', yaw), m_translate((x, 0.0, z)))
    o = sb.obj(name)
    o.add(mats['wood'], xform(wood, m))
    o.add(mats['metal'], xform(metal, m))
    if dark:
        o.add(mats['dark'], xform(dark, m))
    return o


def add_bookcase(sb, name, x, z, yaw, mats, rng, w=0.9, d=0.35, h=2.0, shelves=5, fill=0.8):
    """Bookcase with its back at local z = -d/2, open toward +z, books on each shelf."""
    wood, books = [], []
    hw, hd, t = w / 2, d / 2, 0.02
    for sx in (-1, 1):
        wood += box(sx * hw - (t if sx > 0 else 0), 0.0, -hd, sx * hw + (0 if sx > 0 else t), h - t, hd,
                    skip=('bottom', 'top'))
    wood += box(-hw, h - t, -hd, hw, h, hd)
    wood += box(-hw + t, 0.0, -hd, hw - t, h - t, -hd + 0.01, skip=('bottom', 'top', 'left', 'right'))  # back
    wood += box(-hw + t, 0.0, hd - 0.02, hw - t, 0.06, hd, skip=('bottom', 'top', 'left', 'right', 'back'))  # plinth
    gap = (h - t - 0.08) / shelves
    for i in range(shelves):
        y0 = 0.08 + i * gap
        if i > 0:
            wood += box(-hw + t, y0 - t, -hd + 0.01, hw - t, y0, hd, skip=('left', 'right', 'back'))
        else:
            wood += box(-hw + t, y0 - t, -hd + 0.01, hw - t, y0, hd, skip=('left', 'right', 'back', 'bottom'))
        bx = -hw + t + 0.005
        while True:
            bw = rng.uniform(0.02, 0.05)
            if bx + bw > -hw + t + (w - 2 * t) * fill:
                break
            bh = min(rng.uniform(0.17, 0.29), gap - t - 0.03)
            bd = rng.uniform(0.15, 0.24)
            z0 = -hd + 0.01 + rng.uniform(0.005, 0.04)
            books.append((bx, y0, z0, bx + bw, y0 + bh, z0 + bd))
            bx += bw + 0.004
    m = m_chain(m_rot('y', yaw), m_translate((x, 0.0, z)))
    o = sb.obj(name)
    o.add(mats['wood'], xform(wood, m))
    bk = [[], [], []]
    for j, b in enumerate(books):
        bk[j % 3] += box(*b, skip=('bottom',))
    for j in range(3):
        o.add(mats['books'][j], xform(bk[j], m))
    return o


def add_cupboard(sb, prefix, x, z, yaw, mats, w=1.0, d=0.6, h=2.0, dynamic_box=True):
    """Closed cupboard: carcass (outward faces), an inward-facing closed cavity inside
    it, two closed doors in front (+z local) and a small dynamic box in the cavity."""
    hw, hd, t = w / 2, d / 2, 0.02
    m = m_chain(m_rot('y', yaw), m_translate((x, 0.0, z)))
    carcass = box(-hw, 0.0, -hd, hw, h, hd, skip=('bottom',))
    cav_lo = (-hw + t, t, -hd + t)
    cav_hi = (hw - t, h - t, hd - t)
    cc = ((cav_lo[0] + cav_hi[0]) / 2, (cav_lo[1] + cav_hi[1]) / 2, (cav_lo[2] + cav_hi[2]) / 2)
    cavity = [facing(q, cc, outward=False) for q in box(cav_lo[0], cav_lo[1], cav_lo[2], cav_hi[0], cav_hi[1], cav_hi[2])]
    o = sb.obj(prefix)
    o.add(mats['wood'], xform(carcass, m))
    sb.outward.append((prefix, m_apply(m, (0.0, h / 2, 0.0))))
    inner = sb.obj(prefix + '-inside')
    inner.add(mats['wood'], xform(cavity, m))
    sb.rooms.append((prefix + '-inside', m_apply(m, cc)))
    for side in (-1, 1):
        x0, x1 = (-hw + 0.003, -0.003) if side < 0 else (0.003, hw - 0.003)
        door = box(x0, 0.01, hd + 0.002, x1, h - 0.01, hd + 0.022)
        hx = -0.04 if side < 0 else 0.025
        handle = box(hx, h * 0.45, hd + 0.022, hx + 0.015, h * 0.45 + 0.18, hd + 0.045, skip=('back',))
        dn = '%s-door-%s' % (prefix, 'left' if side < 0 else 'right')
        sb.obj(dn).add(mats['wood'], xform(door, m)).add(mats['metal'], xform(handle, m))
    bx = box(-0.15, t, -0.15, 0.15, t + 0.25, 0.1, skip=('bottom',))
    sb.obj(prefix + '-box', dynamic=dynamic_box).add(mats['box'], xform(bx, m))
    return o


def add_round_table(sb, name, x, z, mats, r=0.6, h=0.73):
    wood, metal = [], []
    wood += cylinder_y(x, z, r, h - 0.03, h, 32)
    metal += cylinder_y(x, z, 0.04, 0.03, h - 0.03, 16, top=False, bottom=False)
    metal += cylinder_y(x, z, 0.28, 0.0, 0.03, 24, bottom=False)
    sb.obj(name).add(mats['wood'], wood).add(mats['metal'], metal)


def add_cabinet(sb, name, x, z, yaw, mats, w=0.5, d=0.6, h=1.3, drawers=4):
    m = m_chain(m_rot('y', yaw), m_translate((x, 0.0, z)))
    hw, hd = w / 2, d / 2
    body = box(-hw, 0.0, -hd, hw, h, hd, skip=('bottom',))
    fronts, handles = [], []
    dh = (h - 0.02) / drawers
    for i in range(drawers):
        y0 = 0.01 + i * dh
        fronts += box(-hw + 0.01, y0 + 0.004, hd, hw - 0.01, y0 + dh - 0.004, hd + 0.015, skip=('back',))
        handles += box(-0.08, y0 + dh - 0.07, hd + 0.015, 0.08, y0 + dh - 0.055, hd + 0.035, skip=('back',))
    sb.obj(name).add(mats['metal2'], xform(body + fronts, m)).add(mats['metal'], xform(handles, m))


def add_whiteboard(sb, name, lo, hi, mats):
    sb.obj(name).add(mats['board'], box(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]))


def office_materials(sb):
    return {
        'wall': sb.material('wall-paint', (0.74, 0.72, 0.67)),
        'floor': sb.material('carpet', (0.32, 0.30, 0.27)),
        'ceiling': sb.material('ceiling-tile', (0.80, 0.80, 0.78)),
        'light': sb.material('light-panel', (0.80, 0.80, 0.80), emission=(14.0, 13.3, 12.0)),
        'fabric': sb.material('chair-fabric', (0.16, 0.22, 0.42)),
        'metal': sb.material('dark-metal', (0.12, 0.12, 0.13)),
        'metal2': sb.material('grey-metal', (0.55, 0.56, 0.57)),
        'wood': sb.material('wood', (0.56, 0.40, 0.24)),
        'dark': sb.material('black-plastic', (0.05, 0.05, 0.05)),
        'board': sb.material('whiteboard', (0.85, 0.85, 0.85)),
        'box': sb.material('cardboard', (0.60, 0.45, 0.28)),
        'books': [sb.material('book-red', (0.55, 0.12, 0.10)), sb.material('book-blue', (0.12, 0.20, 0.50)),
                  sb.material('book-cream', (0.80, 0.75, 0.60))],
    }


def furnish_office(sb, ox, mats, rng, tag='', dynamic_chair=True, extra_chairs=2, mirror=False,
                   cupboard_dynamic=True):
    """Furniture of one 6 x 5 m office whose interior starts at x = ox (z from 0 to 5).
    The dynamic chair sits at a desk along the back wall with ~2.5 m free to its +x."""
    def X(x):
        return ox + (6.0 - x if mirror else x)
    p = tag
    add_desk(sb, p + 'desk-1', X(1.6), 0.46, 0.0, mats)
    add_desk(sb, p + 'desk-2', X(4.8), 0.46, 0.0, mats)
    add_chair(sb, 'chair' if dynamic_chair else p + 'chair-1', X(1.6), 1.45, math.pi + 0.15, mats,
              dynamic=dynamic_chair)
    add_chair(sb, p + 'chair-2', X(4.8), 1.40, math.pi - 0.2, mats)
    add_whiteboard(sb, p + 'whiteboard', (X(3.95) if mirror else X(2.65), 1.0, 0.01),
                   (X(2.65) if mirror else X(3.95), 1.9, 0.03), mats)
    bx = X(0.19) if not mirror else X(0.19)
    add_bookcase(sb, p + 'bookcase-1', bx, 2.2, (0.5 if not mirror else -0.5) * math.pi, mats, rng)
    add_bookcase(sb, p + 'bookcase-2', bx, 3.15, (0.5 if not mirror else -0.5) * math.pi, mats, rng)
    add_cupboard(sb, p + 'cupboard', X(5.69), 2.6, (-0.5 if not mirror else 0.5) * math.pi, mats,
                 dynamic_box=cupboard_dynamic)
    add_cabinet(sb, p + 'filing-cabinet', X(5.69), 1.45, (-0.5 if not mirror else 0.5) * math.pi, mats)
    add_round_table(sb, p + 'meeting-table', X(3.0), 3.55, mats)
    seats = [(2.15, 3.55, 0.5 * math.pi), (3.85, 3.7, -0.5 * math.pi), (3.0, 4.4, math.pi), (3.1, 2.7, 0.1)]
    for i in range(extra_chairs):
        sx, sz, yaw = seats[i]
        add_chair(sb, p + 'chair-%d' % (i + 3), X(sx), sz, -yaw if mirror else yaw, mats)


def office():
    sb = SceneBuilder('office')
    mats = office_materials(sb)
    rng = Rng(1997)
    lights = [(1.2, 1.8, 1.0, 2.2), (4.2, 4.8, 1.0, 2.2), (1.2, 1.8, 3.0, 4.2), (4.2, 4.8, 3.0, 4.2)]
    room(sb, '', (0.0, 0.0, 0.0), (6.0, 3.0, 5.0), OFFICE_TILE, (mats['wall'], mats['floor'], mats['ceiling']),
         lights=lights, light_mat=mats['light'])
    furnish_office(sb, 0.0, mats, rng)
    sb.set_camera((4.6, 1.75, 4.85), (2.2, 0.55, 1.3), math.radians(60.0), 4.0 / 3.0)
    return sb


OFFICE_TILE = 0.4
TWO_OFFICES_TILE = 0.25
DARK_ROOM_TILE = 0.3


def doorway(sb, name, axis, x0, x1, y1, w0, w1, mat):
    """Reveal of a doorway through a wall of thickness w0..w1 along `axis` (0: wall normal
    along x, opening spans z in x0..x1; 2: wall normal along z, opening spans x in x0..x1),
    from the floor to height y1: two jambs, a lintel and a threshold, facing the opening."""
    def P(u, y, w):
        return (w, y, u) if axis == 0 else (u, y, w)
    ref = P((x0 + x1) / 2, y1 / 2, (w0 + w1) / 2)
    quads = [
        [P(x0, 0.0, w0), P(x0, y1, w0), P(x0, y1, w1), P(x0, 0.0, w1)],
        [P(x1, 0.0, w0), P(x1, y1, w0), P(x1, y1, w1), P(x1, 0.0, w1)],
        [P(x0, y1, w0), P(x1, y1, w0), P(x1, y1, w1), P(x0, y1, w1)],
        [P(x0, 0.0, w0), P(x1, 0.0, w0), P(x1, 0.0, w1), P(x0, 0.0, w1)],
    ]
    sb.obj(name).add(mat, [facing(q, ref, outward=False) for q in quads])
    sb.rooms.append((name, ref))


def two_offices():
    sb = SceneBuilder('two-offices')
    mats = office_materials(sb)
    rng = Rng(5)
    rm = (mats['wall'], mats['floor'], mats['ceiling'])
    door = (0.0, 2.1, 3.8, 4.7)  # (y0, y1, z0, z1) on the shared wall
    wall = 0.15
    for tag, ox, hole_side in (('left-', 0.0, 'right'), ('right-', 6.0 + wall, 'left')):
        lights = [(ox + a, ox + b, c, d) for (a, b, c, d) in
                  [(1.2, 1.8, 1.0, 2.2), (4.2, 4.8, 1.0, 2.2), (1.2, 1.8, 3.0, 4.2), (4.2, 4.8, 3.0, 4.2)]]
        room(sb, tag, (ox, 0.0, 0.0), (ox + 6.0, 3.0, 5.0), TWO_OFFICES_TILE, rm, holes={hole_side: [door]},
             lights=lights, light_mat=mats['light'])
    doorway(sb, 'doorway', 0, door[2], door[3], door[1], 6.0, 6.0 + wall, mats['wall'])
    furnish_office(sb, 0.0, mats, rng, tag='left-', dynamic_chair=False, extra_chairs=3, mirror=True,
                   cupboard_dynamic=False)
    furnish_office(sb, 6.0 + wall, mats, rng, tag='right-', dynamic_chair=True, extra_chairs=2,
                   cupboard_dynamic=False)
    sb.set_camera((11.9, 1.8, 4.85), (7.0, 0.8, 2.6), math.radians(65.0), 4.0 / 3.0)
    return sb


def dark_room():
    sb = SceneBuilder('dark-room')
    mats = office_materials(sb)
    mats['door'] = sb.material('door-paint', (0.62, 0.60, 0.55))
    rng = Rng(1010)
    rm = (mats['wall'], mats['floor'], mats['ceiling'])
    h = 2.7
    dx0, dx1, dy1 = 4.55, 5.45, 2.1  # doorway opening
    wz0, wz1 = 2.0, 2.15             # wall between the corridor and the dark room
    lights = [(xc - 0.6, xc + 0.6, 0.8, 1.2) for xc in (1.25, 3.75, 6.25, 8.75)]
    room(sb, 'corridor-', (0.0, 0.0, 0.0), (10.0, h, wz0), DARK_ROOM_TILE, rm,
         holes={'front': [(dx0, dx1, 0.0, dy1)]}, lights=lights, light_mat=mats['light'])
    room(sb, 'dark-room-', (2.0, 0.0, wz1), (8.0, h, wz1 + 5.0), DARK_ROOM_TILE, rm,
         holes={'back': [(dx0, dx1, 0.0, dy1)]})
    doorway(sb, 'doorway', 2, dx0, dx1, dy1, wz0, wz1, mats['wall'])
    # The door: on the corridor side of the wall, 2 mm off it, overlapping the opening by
    # 5 cm on both sides and on top, so that no straight line passes from the corridor into
    # the dark room when it is closed. Its bottom rests on the corridor floor (no bottom face).
    d0, d1 = wz0 - 0.002 - 0.04, wz0 - 0.002
    hinge = [dx0 - 0.05, 0.0, d0]
    sb.obj('door', dynamic=True,
           extras={'hinge': {'point': hinge, 'axis': [0.0, 1.0, 0.0],
                             'note': 'vertical edge of the bounding box (min x, min z); a positive '
                                     'rotation about +y through it opens the door into the corridor. '
                                     'CLI rotations are about the bounding-box centre.'}}
           ).add(mats['door'], box(dx0 - 0.05, 0.0, d0, dx1 + 0.05, dy1 + 0.05, d1, skip=('bottom',)))
    sb.outward.append(('door', (5.0, 1.0, (d0 + d1) / 2)))
    # furniture in the dark room
    add_desk(sb, 'desk', 6.9, wz1 + 0.47, 0.0, mats)
    add_chair(sb, 'chair', 6.8, wz1 + 1.45, math.pi + 0.3, mats)
    add_cabinet(sb, 'filing-cabinet', 3.2, wz1 + 0.32, 0.0, mats)
    add_bookcase(sb, 'bookcase-1', 2.19, 4.4, 0.5 * math.pi, mats, rng)
    add_bookcase(sb, 'bookcase-2', 2.19, 5.35, 0.5 * math.pi, mats, rng)
    add_round_table(sb, 'table', 5.6, 5.3, mats)
    add_chair(sb, 'chair-2', 4.75, 5.2, 0.5 * math.pi, mats)
    sb.set_camera((5.0, 1.6, 6.95), (5.0, 1.0, wz1), math.radians(60.0), 4.0 / 3.0)
    return sb


def furnished_room():
    """A closed room lit by one ceiling panel, with one set of the office furniture: the
    scene for the Cycles reference (bench/cycles). Small enough to path-trace and to solve
    quickly, closed so that no light escapes."""
    sb = SceneBuilder('furnished-room')
    mats = office_materials(sb)
    rng = Rng(612)
    room(sb, '', (0.0, 0.0, 0.0), (6.0, 3.0, 5.0), FURNISHED_ROOM_TILE, (mats['wall'], mats['floor'], mats['ceiling']),
         lights=[(1.4, 2.6, 1.3, 1.9)], light_mat=mats['light'])
    add_desk(sb, 'desk', 1.6, 0.46, 0.0, mats)
    add_chair(sb, 'chair', 1.7, 1.4, math.pi + 0.25, mats, dynamic=True)
    add_cabinet(sb, 'filing-cabinet', 3.3, 0.32, 0.0, mats)
    add_bookcase(sb, 'bookcase', 0.19, 2.6, 0.5 * math.pi, mats, rng)
    sb.set_camera((5.6, 1.6, 4.6), (1.9, 1.15, 1.0), math.radians(50.0), 4.0 / 3.0)
    return sb


FURNISHED_ROOM_TILE = 0.75


def lamp_room():
    """The furnished room lit by punctual lights only (KHR_lights_punctual, as modelling tools
    export lamps): a point light under the ceiling and a spot over the desk, no emissive panel."""
    sb = SceneBuilder('lamp-room')
    mats = office_materials(sb)
    rng = Rng(612)
    room(sb, '', (0.0, 0.0, 0.0), (6.0, 3.0, 5.0), FURNISHED_ROOM_TILE, (mats['wall'], mats['floor'], mats['ceiling']))
    add_desk(sb, 'desk', 1.6, 0.46, 0.0, mats)
    add_chair(sb, 'chair', 1.7, 1.4, math.pi + 0.25, mats, dynamic=True)
    add_cabinet(sb, 'filing-cabinet', 3.3, 0.32, 0.0, mats)
    add_bookcase(sb, 'bookcase', 0.19, 2.6, 0.5 * math.pi, mats, rng)
    sb.point_light('bulb', (3.4, 2.5, 2.6), (1.0, 0.93, 0.82), 1.2)
    sb.spot_light('desk-spot', (1.6, 2.9, 0.9), (1.6, 0.74, 0.5), (1.0, 0.97, 0.9), 4.0, 0.35, 0.6)
    sb.set_camera((5.6, 1.6, 4.6), (1.9, 1.15, 1.0), math.radians(50.0), 4.0 / 3.0)
    return sb


def textured_room():
    """The furnished room with base colour textures, as modelling tools write them (a texture
    per material, TEXCOORD_0): a checkered floor of 0.75 m tiles and a striped hanging on the
    wall. Each element reflects the texels under it, and the viewer draws the texels."""
    sb = SceneBuilder('textured-room')
    mats = office_materials(sb)
    light_tile, dark_tile = (205, 195, 175), (70, 58, 50)
    # 32 texels a tile, so that the viewer's bilinear filtering blurs only the tiles' edges.
    floor = sb.texture(sb.material('checker-floor', (0.9, 0.9, 0.9)), 64, 64,
                       [light_tile if (x // 32 + y // 32) % 2 == 0 else dark_tile for y in range(64) for x in range(64)],
                       2 * FURNISHED_ROOM_TILE)
    stripes = [(190, 40, 35), (235, 190, 60), (40, 90, 170), (230, 225, 215)]
    hanging = sb.texture(sb.material('hanging', (0.9, 0.9, 0.9)), 64, 16,
                         [stripes[(x // 16) % 4] for _ in range(16) for x in range(64)], 1.2)
    rng = Rng(612)
    room(sb, '', (0.0, 0.0, 0.0), (6.0, 3.0, 5.0), FURNISHED_ROOM_TILE, (mats['wall'], floor, mats['ceiling']),
         lights=[(1.4, 2.6, 1.3, 1.9)], light_mat=mats['light'])
    add_desk(sb, 'desk', 1.6, 0.46, 0.0, mats)
    add_chair(sb, 'chair', 1.7, 1.4, math.pi + 0.25, mats, dynamic=True)
    add_bookcase(sb, 'bookcase', 0.19, 2.6, 0.5 * math.pi, mats, rng)
    # 2 cm off the wall x = 0, facing into the room.
    panel = [(0.02, 1.0, 0.8), (0.02, 1.0, 2.0), (0.02, 2.2, 2.0), (0.02, 2.2, 0.8)]
    sb.obj('hanging').add(hanging, [facing(panel, (1.0, 1.6, 1.4), outward=False)])
    sb.set_camera((5.6, 1.6, 4.6), (1.9, 1.15, 1.0), math.radians(50.0), 4.0 / 3.0)
    return sb


def building_floor(rooms_per_side=30):
    """A floor of a building at the scale users bring (about 100k polygons): a corridor with
    furnished rooms on both sides. Each room is closed but for its doorway onto the corridor (its
    door stands open inside, against the wall), has its own ceiling panel and the furnished room's
    furniture; the corridor has panels along its ceiling. Rooms on the far side are the near ones
    turned by 180 degrees about their centre. One chair (room s00) is marked dynamic."""
    sb = SceneBuilder('building-floor')
    mats = office_materials(sb)
    mats['door'] = sb.material('door-paint', (0.62, 0.60, 0.55))
    rng = Rng(2026)
    rm = (mats['wall'], mats['floor'], mats['ceiling'])
    W, D, H, wall = 6.0, 5.0, 3.0, 0.15
    cw, ch = 2.4, 2.7                     # corridor width and height
    pitch = W + wall
    length = rooms_per_side * pitch - wall
    zc0 = D + wall                        # corridor z range
    zc1 = zc0 + cw
    zn0 = zc1 + wall                      # far-side rooms start here
    door_x, door_w, door_h = 4.6, 0.9, 2.1  # doorway in room coordinates (x from the room's left)
    south, north = [], []
    for i in range(rooms_per_side):
        ox = i * pitch
        south.append((ox + door_x, ox + door_x + door_w, 0.0, door_h))
        # the far-side room is turned: its doorway's x is mirrored about the room's centre
        north.append((ox + W - door_x - door_w, ox + W - door_x, 0.0, door_h))
    corridor_lights = [(x - 0.6, x + 0.6, zc0 + cw / 2 - 0.2, zc0 + cw / 2 + 0.2)
                       for x in [1.5 + 3.0 * k for k in range(int((length - 1.5) // 3.0) + 1)]]
    room(sb, 'corridor-', (0.0, 0.0, zc0), (length, ch, zc1), 1.0, rm, holes={'back': south, 'front': north},
         lights=corridor_lights, light_mat=mats['light'])
    for i in range(rooms_per_side):
        for side in ('s', 'n'):
            ox = i * pitch
            oz = 0.0 if side == 's' else zn0
            tag = 'room-%s%02d-' % (side, i)

            def place(x, z, yaw=0.0):
                # room coordinates: x from the left wall, z from the wall opposite the doorway
                if side == 's':
                    return ox + x, oz + z, yaw
                return ox + W - x, oz + D - z, yaw + math.pi

            if side == 's':
                holes = {'front': [south[i]]}
                doorway(sb, tag + 'doorway', 2, south[i][0], south[i][1], door_h, D, zc0, mats['wall'])
            else:
                holes = {'back': [north[i]]}
                doorway(sb, tag + 'doorway', 2, north[i][0], north[i][1], door_h, zc1, zn0, mats['wall'])
            lx, lz, _ = place(3.0, 1.6)
            room(sb, tag, (ox, 0.0, oz), (ox + W, H, oz + D), FURNISHED_ROOM_TILE, rm, holes=holes,
                 lights=[(lx - 0.6, lx + 0.6, lz - 0.3, lz + 0.3)], light_mat=mats['light'])
            x, z, yaw = place(1.6, 0.46)
            add_desk(sb, tag + 'desk', x, z, yaw, mats)
            x, z, yaw = place(1.7, 1.4, math.pi + 0.25)
            dynamic = side == 's' and i == 0
            add_chair(sb, 'chair' if dynamic else tag + 'chair', x, z, yaw, mats, dynamic=dynamic)
            x, z, yaw = place(3.3, 0.32)
            add_cabinet(sb, tag + 'filing-cabinet', x, z, yaw, mats)
            x, z, yaw = place(0.19, 2.6, 0.5 * math.pi)
            add_bookcase(sb, tag + 'bookcase', x, z, yaw, mats, rng)
            # the door, open: a slab at right angles to the doorway wall, hinged at the doorway's
            # right-hand edge, 2 mm off everything
            a = place(door_x + door_w + 0.002, D - 0.002 - door_w)
            b = place(door_x + door_w + 0.042, D - 0.002)
            sb.obj(tag + 'door').add(mats['door'], box(min(a[0], b[0]), 0.0, min(a[1], b[1]),
                                                      max(a[0], b[0]), door_h, max(a[1], b[1]),
                                                      skip=('bottom',)))
            sb.outward.append((tag + 'door', ((a[0] + b[0]) / 2, 1.0, (a[1] + b[1]) / 2)))
    sb.set_camera((0.8, 1.6, zc0 + cw / 2), (12.0, 1.2, zc0 + cw / 2), math.radians(60.0), 4.0 / 3.0)
    return sb


# ---------------------------------------------------------------------------
# Checking written files


def read_gltf(path):
    with open(path, 'rb') as f:
        gl = json.loads(f.read().decode('utf-8'))
    assert len(gl['buffers']) == 1
    uri = gl['buffers'][0]['uri']
    prefix = 'data:application/octet-stream;base64,'
    assert uri.startswith(prefix)
    buf = base64.b64decode(uri[len(prefix):])
    assert len(buf) == gl['buffers'][0]['byteLength']

    def acc(i):
        a = gl['accessors'][i]
        v = gl['bufferViews'][a['bufferView']]
        off = v.get('byteOffset', 0) + a.get('byteOffset', 0)
        if a['type'] == 'VEC3':
            assert a['componentType'] == 5126
            vals = struct.unpack_from('<%df' % (3 * a['count']), buf, off)
            return [tuple(vals[3 * k:3 * k + 3]) for k in range(a['count'])]
        fmt = {5123: 'H', 5125: 'I'}[a['componentType']]
        return list(struct.unpack_from('<%d%s' % (a['count'], fmt), buf, off))

    objects = {}
    for node in gl['nodes']:
        if 'mesh' not in node:
            continue
        polys = []
        for prim in gl['meshes'][node['mesh']]['primitives']:
            pos = acc(prim['attributes']['POSITION'])
            idx = acc(prim['indices'])
            tris = [tuple(idx[k:k + 3]) for k in range(0, len(idx), 3)]
            k = 0
            while k < len(tris):
                t = tris[k]
                if k + 1 < len(tris):
                    u = tris[k + 1]
                    if u[0] == t[0] and u[1] == t[2]:
                        q = [pos[t[0]], pos[t[1]], pos[t[2]], pos[u[2]]]
                        n1 = normalize(newell([pos[i] for i in t]))
                        n2 = normalize(newell([pos[i] for i in u]))
                        if dot(n1, n2) > 0.99999:
                            polys.append((prim['material'], q))
                            k += 2
                            continue
                polys.append((prim['material'], [pos[i] for i in t]))
                k += 1
        objects[node['name']] = (node, polys)
    return gl, objects


def project2d(poly, n):
    ax = max(range(3), key=lambda i: abs(n[i]))
    o = [i for i in range(3) if i != ax]
    pts = [(p[o[0]], p[o[1]]) for p in poly]
    # make counter-clockwise
    a = sum(pts[i - 1][0] * pts[i][1] - pts[i][0] * pts[i - 1][1] for i in range(len(pts)))
    return pts if a > 0 else pts[::-1]


def clip_area(p, q):
    """Area of the intersection of two convex CCW 2D polygons."""
    out = p
    for i in range(len(q)):
        a, b = q[i - 1], q[i]
        inp, out = out, []
        if not inp:
            break
        for j in range(len(inp)):
            c, d = inp[j - 1], inp[j]
            sc = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
            sd = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0])
            if sd >= 0:
                if sc < 0:
                    t = sc / (sc - sd)
                    out.append((c[0] + (d[0] - c[0]) * t, c[1] + (d[1] - c[1]) * t))
                out.append(d)
            elif sc >= 0:
                t = sc / (sc - sd)
                out.append((c[0] + (d[0] - c[0]) * t, c[1] + (d[1] - c[1]) * t))
    if len(out) < 3:
        return 0.0
    return 0.5 * abs(sum(out[i - 1][0] * out[i][1] - out[i][0] * out[i - 1][1] for i in range(len(out))))


def check_overlaps(allpolys, gap=5e-4):
    """Find pairs of (anti)parallel polygons closer than `gap` along the normal that overlap."""
    groups = {}
    for name, poly in allpolys:
        n = normalize(newell(poly))
        s = 1.0
        for c in n:
            if abs(c) > 1e-6:
                s = 1.0 if c > 0 else -1.0
                break
        cn = mul(n, s)
        key = tuple(round(c, 3) + 0.0 for c in cn)
        d = dot(cn, centroid(poly))
        p2 = project2d(poly, cn)
        xs = [p[0] for p in p2]
        ys = [p[1] for p in p2]
        groups.setdefault(key, []).append((d, name, p2, (min(xs), max(xs), min(ys), max(ys)), cn, centroid(poly)))
    bad = []
    for key, items in groups.items():
        items.sort(key=lambda t: t[0])
        for i in range(len(items)):
            d1, n1, p1, b1, c1, m1 = items[i]
            for j in range(i + 1, len(items)):
                d2, n2, p2, b2, c2, m2 = items[j]
                if d2 - d1 > gap:
                    break
                # normals that only round to the same key are not parallel planes (a turned
                # chair's cushion faces, 180 m from the origin where d = n.c spreads): the
                # distance that counts is between the faces, where they are
                if abs(dot(c1, sub(m2, m1))) > gap:
                    continue
                if min(b1[1], b2[1]) - max(b1[0], b2[0]) <= 1e-6 or min(b1[3], b2[3]) - max(b1[2], b2[2]) <= 1e-6:
                    continue
                a = clip_area(p1, p2)
                if a > 1e-7:
                    bad.append((n1, n2, a))
    return bad


def check_scene(sb, path, expected_bytes):
    errors = []
    with open(path, 'rb') as f:
        data = f.read()
    if data != expected_bytes:
        errors.append('file differs from a fresh generation (not deterministic or stale)')
    limit = 6 if sb.name == 'building-floor' else 3  # the scale scene is big by design
    if len(data) > limit * 1024 * 1024:
        errors.append('file larger than %d MB (%d bytes)' % (limit, len(data)))
    gl, objects = read_gltf(path)
    names = [n['name'] for n in gl['nodes']]
    if len(set(names)) != len(names):
        errors.append('duplicate node names')
    for m in gl['materials']:
        if not m.get('name'):
            errors.append('unnamed material')
        bc = m['pbrMetallicRoughness']['baseColorFactor']
        if not all(0.0 <= c < 1.0 for c in bc[:3]) or bc[3] != 1.0:
            errors.append('material %s reflectance out of [0,1)' % m['name'])
        if 'KHR_materials_emissive_strength' in m.get('extensions', {}):
            if 'KHR_materials_emissive_strength' not in gl.get('extensionsUsed', []):
                errors.append('emissive strength used but not listed in extensionsUsed')
    total = 0
    allpolys = []
    lo = [1e30] * 3
    hi = [-1e30] * 3
    magnitude = max(abs(c) for _, (_, polys) in objects.items() for _, poly in polys for p in poly for c in p)
    for name, (node, polys) in objects.items():
        if 'translation' in node or 'rotation' in node or 'matrix' in node or 'scale' in node:
            errors.append('%s: mesh node has a transform' % name)
        total += len(polys)
        for mat, poly in polys:
            try:
                validate_polygon(poly, name, magnitude)
            except AssertionError as e:
                errors.append(str(e))
            allpolys.append((name, poly))
            for p in poly:
                for i in range(3):
                    lo[i] = min(lo[i], p[i])
                    hi[i] = max(hi[i], p[i])
    if total != sb.polygon_count():
        errors.append('polygon count after quad merging %d != generated %d' % (total, sb.polygon_count()))
    for name, ref in sb.rooms:
        for mat, poly in objects[name][1]:
            if dot(newell(poly), sub(ref, centroid(poly))) <= 0:
                errors.append('%s: a face does not point into the room' % name)
                break
    for name, ref in sb.outward:
        for mat, poly in objects[name][1]:
            if dot(newell(poly), sub(centroid(poly), ref)) <= 0:
                errors.append('%s: a face does not point outward' % name)
                break
    # everything inside the rooms' bounds
    rlo = [1e30] * 3
    rhi = [-1e30] * 3
    for name, ref in sb.rooms:
        for mat, poly in objects[name][1]:
            for p in poly:
                for i in range(3):
                    rlo[i] = min(rlo[i], p[i])
                    rhi[i] = max(rhi[i], p[i])
    if any(lo[i] < rlo[i] - 1e-5 or hi[i] > rhi[i] + 1e-5 for i in range(3)):
        errors.append('geometry outside the rooms: %r %r vs %r %r' % (lo, hi, rlo, rhi))
    # the same float32 rounding moves faces by up to 4 of its units
    for a, b, area in check_overlaps(allpolys, 5e-4 - 4 * 1.2e-7 * magnitude)[:10]:
        errors.append('coincident overlapping faces: %s / %s (%.3g m2)' % (a, b, area))
    cams = [n for n in gl['nodes'] if 'camera' in n]
    if len(cams) != 1:
        errors.append('expected one camera node')
    dyn = [n['name'] for n in gl['nodes'] if n.get('extras', {}).get('dynamic')]
    return errors, total, dyn


# ---------------------------------------------------------------------------

SCENES = [('cornell-box', cornell), ('office', office), ('two-offices', two_offices), ('dark-room', dark_room),
          ('furnished-room', furnished_room), ('lamp-room', lamp_room), ('textured-room', textured_room),
          ('building-floor', building_floor)]


def main(argv=None):
    ap = argparse.ArgumentParser(description='Generate the shipped glTF test scenes (deterministic).')
    ap.add_argument('--out', default=HERE, help='output folder (default: the folder of this script)')
    ap.add_argument('--check', action='store_true',
                    help='after writing, re-read the files and validate counts, windings, geometry')
    ap.add_argument('--only', nargs='*', default=None, help='only these scenes (e.g. cornell-box office)')
    ap.add_argument('--no-write', action='store_true', help='with --check: check existing files, do not write')
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    ok = True
    for name, fn in SCENES:
        if args.only and name not in args.only:
            continue
        sb = fn()
        data = build_gltf(sb)
        path = os.path.join(args.out, name + '.gltf')
        if not args.no_write:
            with open(path, 'wb') as f:
                f.write(data)
        dyn = [o.name for o in sb.objects if o.dynamic]
        print('%-20s %6d polygons  %8d bytes  lights %d  dynamic %s' % (
            name + '.gltf', sb.polygon_count(), len(data),
            sum(1 for o in sb.objects if any(sb.materials[m][1] for m, _ in o.parts)) + len(sb.lights),
            ','.join(dyn)))
        if args.check:
            errors, total, _ = check_scene(sb, path, data)
            for e in errors:
                print('  ERROR: ' + e)
            ok = ok and not errors
            print('  check: %s (%d polygons after quad merging)' % ('ok' if not errors else 'FAILED', total))
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
