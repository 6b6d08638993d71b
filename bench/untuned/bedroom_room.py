"""A bedroom none of the settings were tuned on: two table lamps, each a small glowing box inside
an open 16-sided shade (light leaves only through the shade's top and bottom openings), on
bedside tables; a window whose glowing pane lies behind twelve horizontal blind slats 2 mm
thick, tilted 30 degrees; a bed (a base and a headboard against the wall), a wardrobe, and a
rug on the floor. The camera looks from the door toward the bed.

    python3 bench/untuned/bedroom_room.py OUT.gltf
"""
import json
import math
import sys

from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, quad, views

materials = [
    material("plaster", (0.78, 0.76, 0.72)),
    material("floor-oak", (0.42, 0.3, 0.2)),
    material("linen", (0.75, 0.72, 0.66)),
    material("walnut", (0.3, 0.2, 0.13)),
    material("shade", (0.85, 0.8, 0.7)),
    material("bulb", (0.8, 0.8, 0.8), (1.0, 0.85, 0.65), 40.0),
    material("sky", (0.8, 0.8, 0.8), (0.8, 0.9, 1.0), 2.5),
    material("slat", (0.7, 0.7, 0.7)),
    material("rug-blue", (0.2, 0.25, 0.45)),
]
W, D, H = 4.0, 3.6, 2.5


floor = add_mesh("floor", [quad((0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0))], 1)
ceiling = add_mesh("ceiling", [quad((0, H, 0), (W, H, 0), (W, H, D), (0, H, D))], 0)
# The window in the x = W wall: z 1.0..2.4, y 0.9..2.1; its glowing pane 10 cm out, a reveal around.
wz0, wz1, wy0, wy1, wd = 1.0, 2.4, 0.9, 2.1, 0.1
walls = add_mesh("walls", [
    quad((0, 0, 0), (W, 0, 0), (W, H, 0), (0, H, 0)),      # z = 0 (bed wall), faces +z
    quad((0, 0, 0), (0, H, 0), (0, H, D), (0, 0, D)),      # x = 0, faces +x
    quad((0, 0, D), (0, H, D), (W, H, D), (W, 0, D)),      # z = D, faces -z
    quad((W, 0, 0), (W, 0, wz0), (W, H, wz0), (W, H, 0)),  # x = W around the window, faces -x
    quad((W, 0, wz1), (W, 0, D), (W, H, D), (W, H, wz1)),
    quad((W, 0, wz0), (W, 0, wz1), (W, wy0, wz1), (W, wy0, wz0)),
    quad((W, wy1, wz0), (W, wy1, wz1), (W, H, wz1), (W, H, wz0)),
    quad((W, wy0, wz0), (W, wy0, wz1), (W + wd, wy0, wz1), (W + wd, wy0, wz0)),  # sill, faces up
    quad((W, wy1, wz0), (W + wd, wy1, wz0), (W + wd, wy1, wz1), (W, wy1, wz1)),  # head, faces down
    quad((W, wy0, wz0), (W + wd, wy0, wz0), (W + wd, wy1, wz0), (W, wy1, wz0)),  # reveal, faces +z
    quad((W, wy0, wz1), (W, wy1, wz1), (W + wd, wy1, wz1), (W + wd, wy0, wz1)),  # reveal, faces -z
], 0)
pane = add_mesh("window", [quad((W + wd, wy0, wz0), (W + wd, wy0, wz1), (W + wd, wy1, wz1), (W + wd, wy1, wz0))], 6)
# Blind slats: 12 slats 6 cm deep, 2 mm thick, tilted 30 degrees, 4 cm inside the window plane.
slats = []
for k in range(12):
    yc = wy0 + 0.05 + k * (wy1 - wy0 - 0.1) / 11
    c, s_ = 0.03 * math.cos(math.radians(30)), 0.03 * math.sin(math.radians(30))
    xc = W - 0.04
    a = (xc - c, yc - s_)
    b = (xc + c, yc + s_)
    t = 0.001
    top = [(a[0], a[1] + t), (b[0], b[1] + t)]
    bot = [(a[0], a[1] - t), (b[0], b[1] - t)]
    slats.append(quad((top[0][0], top[0][1], wz0), (top[0][0], top[0][1], wz1), (top[1][0], top[1][1], wz1), (top[1][0], top[1][1], wz0)))
    slats.append(quad((bot[0][0], bot[0][1], wz0), (bot[1][0], bot[1][1], wz0), (bot[1][0], bot[1][1], wz1), (bot[0][0], bot[0][1], wz1)))
blinds = add_mesh("blinds", slats, 7)
# The bed against the z = 0 wall, centred in x, and its headboard.
bed = add_mesh("bed", box(1.2, 0.0, 0.05, 2.8, 0.5, 2.1) + box(1.15, 0.0, 0.0, 2.85, 1.1, 0.05), 2)
# Bedside tables and the lamps on them.
tables = add_mesh("bedside-tables", box(0.6, 0.0, 0.05, 1.05, 0.55, 0.45) + box(2.95, 0.0, 0.05, 3.4, 0.55, 0.45), 3)
shade_quads, bulbs = [], []
for cx in (0.825, 3.175):
    cz, r, y0, y1 = 0.25, 0.14, 0.72, 0.95
    for k in range(16):
        a0, a1 = 2 * math.pi * k / 16, 2 * math.pi * (k + 1) / 16
        p0 = (cx + r * math.cos(a0), cz + r * math.sin(a0))
        p1 = (cx + r * math.cos(a1), cz + r * math.sin(a1))
        # Outward faces and, 3 mm inside them, inward faces: a shade has two sides (coincident
        # ones would leave a path tracer to pick either at random).
        q0 = (cx + (r - 0.003) * math.cos(a0), cz + (r - 0.003) * math.sin(a0))
        q1 = (cx + (r - 0.003) * math.cos(a1), cz + (r - 0.003) * math.sin(a1))
        shade_quads.append(quad((p0[0], y0, p0[1]), (p0[0], y1, p0[1]), (p1[0], y1, p1[1]), (p1[0], y0, p1[1])))
        shade_quads.append(quad((q0[0], y0, q0[1]), (q1[0], y0, q1[1]), (q1[0], y1, q1[1]), (q0[0], y1, q0[1])))
    bulbs += box(cx - 0.03, 0.8, cz - 0.03, cx + 0.03, 0.86, cz + 0.03)
shades = add_mesh("shades", shade_quads, 4)
bulb = add_mesh("bulbs", bulbs, 5)
stems = add_mesh("lamp-stems", box(0.815, 0.55, 0.24, 0.835, 0.8, 0.26) + box(3.165, 0.55, 0.24, 3.185, 0.8, 0.26), 3)
wardrobe = add_mesh("wardrobe", box(0.0, 0.0, 2.4, 0.6, 2.1, 3.5), 3)
rug = add_mesh("rug", [quad((1.0, 0.005, 2.0), (1.0, 0.005, 3.2), (3.0, 0.005, 3.2), (3.0, 0.005, 2.0))], 8)

names = ["floor", "ceiling", "walls", "window", "blinds", "bed", "bedside-tables", "shades", "bulbs", "lamp-stems",
         "wardrobe", "rug"]
ids = [floor, ceiling, walls, pane, blinds, bed, tables, shades, bulb, stems, wardrobe, rug]
nodes = [{"name": n, "mesh": m} for n, m in zip(names, ids)]
# From near the door (x 3.3, z 3.4) at eye height, looking toward the bed, slightly down.
nodes.append({"name": "camera", "camera": 0, "translation": [3.2, 1.6, 3.45],
              "rotation": [-0.0953, 0.1040, 0.0100, 0.9899]})
g = {"asset": {"version": "2.0", "generator": "untuned-bedroom"}, "scene": 0,
     "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
     "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.15, "aspectRatio": 1.333, "znear": 0.05}}],
     "extensionsUsed": ["KHR_materials_emissive_strength"]}
json.dump(g, open(sys.argv[1] if len(sys.argv) > 1 else "bedroom.gltf", "w"))
