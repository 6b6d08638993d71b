#!/usr/bin/env python3
# A room none of the settings were tuned on: a CAD-triangulated wall with a
# window (into a closed niche) and a doorway (into a closet, closed by a
# dynamic door 2 mm off the wall), a ceiling panel, a point lamp and a spot,
# a table overlapping a cabinet, a chair. Closed: every opening leads into a box.
# Usage: python3 bench/untuned/openings_room.py OUT.gltf; its script:
# bench/untuned/openings_room_script.json (a lamp brightened 8 times, the panel
# dimmed, the door opened 40 degrees, the chair moved, over 4 frames).
import json, struct, base64, sys
objs = []  # (name, material, tris(list of 3 xyz), extras)
def quad(a, b, c, d): return [(a, b, c), (a, c, d)]
def box(x0, y0, z0, x1, y1, z1, inward=False):
    P = lambda x, y, z: (x, y, z)
    f = []
    f += quad(P(x0,y0,z0), P(x1,y0,z0), P(x1,y0,z1), P(x0,y0,z1))  # bottom -y
    f += quad(P(x0,y1,z0), P(x0,y1,z1), P(x1,y1,z1), P(x1,y1,z0))  # top +y
    f += quad(P(x0,y0,z0), P(x0,y1,z0), P(x1,y1,z0), P(x1,y0,z0))  # -z
    f += quad(P(x0,y0,z1), P(x1,y0,z1), P(x1,y1,z1), P(x0,y1,z1))  # +z
    f += quad(P(x0,y0,z0), P(x0,y0,z1), P(x0,y1,z1), P(x0,y1,z0))  # -x
    f += quad(P(x1,y0,z0), P(x1,y1,z0), P(x1,y1,z1), P(x1,y0,z1))  # +x
    if inward: f = [(a, c, b) for (a, b, c) in f]
    return f
W, H, D = 5.0, 2.8, 4.0
room = box(0, 0, 0, W, H, D, inward=True)
# drop the room's x=0 wall (faces 8,9 are -x) and rebuild it with openings
room = [t for t in room if not all(abs(p[0]) < 1e-9 for p in t)]
objs.append(("room", "plaster", room, None))
# x=0 wall seen from inside faces +x. Window z 1.0..2.0, y 1.0..2.0; doorway z 2.6..3.5, y 0..2.1
wall_pts = []
def P(y, z): return (0.0, y, z)
# CAD-like: outer corners + opening corners, triangles fanned as slivers
A, B, C, Dd = P(0, 0), P(0, D), P(H, D), P(H, 0)
w = [P(1, 1), P(1, 2), P(2, 2), P(2, 1)]     # window corners (y,z)
d = [P(0, 2.6), P(2.1, 2.6), P(2.1, 3.5), P(0, 3.5)]  # door corners
def tri(a, b, c):  # orient to face +x
    ab = [b[i]-a[i] for i in range(3)]; ac = [c[i]-a[i] for i in range(3)]
    nx = ab[1]*ac[2]-ab[2]*ac[1]
    return (a, b, c) if nx > 0 else (a, c, b)
T = []
# region split: z 0..1 strip, window column z1..2 (below/above), z 2..2.6, door column z2.6..3.5 (above), z3.5..4
def rect(y0, z0, y1, z1, slivers):
    pts = [P(y0, z0), P(y0, z1), P(y1, z1), P(y1, z0)]
    if not slivers: return [tri(pts[0], pts[1], pts[2]), tri(pts[0], pts[2], pts[3])]
    # points along the bottom edge, fanned to the top corners: slivers
    n = 6; out = []
    bottom = [P(y0, z0 + (z1 - z0) * i / n) for i in range(n + 1)]
    for i in range(n): out.append(tri(bottom[i], bottom[i+1], P(y1, z1) if i >= n//2 else P(y1, z0)))
    out.append(tri(bottom[n//2], P(y1, z1), P(y1, z0)))
    return out
T += rect(0, 0, H, 1.0, True)
T += rect(0, 1.0, 1.0, 2.0, True); T += rect(2.0, 1.0, H, 2.0, True)
T += rect(0, 2.0, H, 2.6, True)
T += rect(2.1, 2.6, H, 3.5, True)
T += rect(0, 3.5, H, 4.0, True)
objs.append(("wall-openings", "plaster", T, None))
# niche behind the window (closed box outside x<0), closet behind the door
niche = box(-0.5, 1.0, 1.0, 0.0, 2.0, 2.0, inward=True)
niche = [t for t in niche if not all(abs(p[0]) < 1e-9 for p in t)]
objs.append(("niche", "blue", niche, None))
closet = box(-1.2, 0, 2.4, 0.0, 2.4, 3.7, inward=True)
closet = [t for t in closet if not all(abs(p[0]) < 1e-9 for p in t)]
# the closet's x=0 side: the room wall's back around the doorway is the room's wall... keep closet open there (it meets the wall)
objs.append(("closet", "wood-light", closet, None))
# closet's inner face of the wall (facing -x) around the door, so the closet is closed
cw = []
def rectm(y0, z0, y1, z1):  # faces -x
    a, b, c, dd = (0.0, y0, z0), (0.0, y1, z0), (0.0, y1, z1), (0.0, y0, z1)
    return [(a, b, c), (a, c, dd)]
cw += rectm(0, 2.4, 2.4, 2.6); cw += rectm(0, 3.5, 2.4, 3.7); cw += rectm(2.1, 2.6, 2.4, 3.5)
objs.append(("closet-wall", "wood-light", cw, None))
# door 2 mm inside the closet, covering the doorway with overlap
objs.append(("door", "wood", box(-0.042, 0.0, 2.55, -0.002, 2.15, 3.55), {"dynamic": True}))
# ceiling panel
objs.append(("panel", "panel", [((2.0, H - 0.01, 1.5), (3.0, H - 0.01, 1.5), (3.0, H - 0.01, 2.5)), ((2.0, H - 0.01, 1.5), (3.0, H - 0.01, 2.5), (2.0, H - 0.01, 2.5))], None))
# table overlapping a cabinet
objs.append(("table", "wood", box(2.8, 0.70, 0.4, 4.4, 0.75, 1.4) + box(2.9, 0, 0.5, 2.95, 0.7, 0.55) + box(4.25, 0, 1.25, 4.3, 0.7, 1.3), None))
objs.append(("cabinet", "grey", box(4.0, 0, 0.2, 4.9, 1.1, 0.8), None))
objs.append(("chair", "red", box(2.2, 0.42, 2.6, 2.7, 0.47, 3.1) + box(2.2, 0.47, 3.05, 2.7, 1.0, 3.1) + box(2.25, 0, 2.65, 2.3, 0.42, 2.7), {"dynamic": True}))
mats = {"plaster": [0.78, 0.76, 0.72], "blue": [0.2, 0.3, 0.6], "wood-light": [0.7, 0.6, 0.45], "wood": [0.5, 0.35, 0.2],
        "grey": [0.5, 0.5, 0.5], "red": [0.6, 0.15, 0.1], "panel": [0.8, 0.8, 0.8]}
mnames = list(mats)
buf = bytearray(); views = []; accs = []; meshes = []; nodes = []
for name, m, tris, extras in objs:
    pos = [c for t in tris for p in t for c in p]
    off = len(buf); buf += struct.pack('<%df' % len(pos), *pos)
    views.append({"buffer": 0, "byteOffset": off, "byteLength": 4 * len(pos)})
    xs = pos[0::3]; ys = pos[1::3]; zs = pos[2::3]
    accs.append({"bufferView": len(views) - 1, "componentType": 5126, "type": "VEC3", "count": len(pos) // 3,
                 "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]})
    meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accs) - 1}, "material": mnames.index(m)}]})
    n = {"name": name, "mesh": len(meshes) - 1}
    if extras: n["extras"] = extras
    nodes.append(n)
materials = []
for k, v in mats.items():
    mm = {"name": k, "pbrMetallicRoughness": {"baseColorFactor": v + [1]}}
    if k == "panel": mm["emissiveFactor"] = [1, 1, 1]; mm["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": 3.0}}
    materials.append(mm)
nodes.append({"name": "lamp", "translation": [1.2, 1.6, 0.8], "extensions": {"KHR_lights_punctual": {"light": 0}}})
nodes.append({"name": "spot", "translation": [4.5, 2.6, 3.5], "rotation": [-0.7071, 0, 0, 0.7071], "extensions": {"KHR_lights_punctual": {"light": 1}}})
nodes.append({"name": "camera", "translation": [4.6, 1.6, 3.8], "rotation": [-0.05, 0.38, 0.02, 0.92], "camera": 0})
g = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
     "extensions": {"KHR_lights_punctual": {"lights": [{"name": "lamp", "type": "point", "intensity": 0.8, "color": [1, 0.9, 0.8]},
        {"name": "spot", "type": "spot", "intensity": 3.0, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}}]}},
     "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes, "materials": materials,
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05, "zfar": 50}}],
     "accessors": accs, "bufferViews": views,
     "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}]}
json.dump(g, open(sys.argv[1], "w"))
