"""A room none of the settings were tuned on, lit only by indirect light: two uplights (glowing
quads facing up on top of tall cabinets) light a 4.2 m high white ceiling, and everything else
sees the ceiling's reflection. A mezzanine slab across the back at 2.3 m, with a balustrade of
4 cm bars, shades a sofa and a table beneath it, which the light reaches only after a second
bounce off the floor and walls. One wall is red; a dynamic ottoman stands in the open part. The
camera looks from the front wall toward the mezzanine.

    python3 bench/untuned/uplight_room.py OUT.gltf
"""
import json
import sys

from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, quad, views

materials = [
    material("ceiling-white", (0.85, 0.85, 0.83)),
    material("wall-warm", (0.7, 0.66, 0.6)),
    material("floor-wood", (0.28, 0.2, 0.14)),
    material("wall-red", (0.6, 0.2, 0.15)),
    material("concrete", (0.5, 0.5, 0.5)),
    material("metal", (0.3, 0.3, 0.32)),
    material("sofa-blue", (0.2, 0.3, 0.5)),
    material("cabinet-wood", (0.5, 0.36, 0.22)),
    material("uplight", (0.8, 0.8, 0.8), (1.0, 0.9, 0.75), 12.0),
]
W, D, H = 6.0, 4.5, 4.2


# The shell, facing inward: floor, ceiling, three warm walls and a red one at x = W.
floor = add_mesh("floor", [quad((0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0))], 2)
ceiling = add_mesh("ceiling", [quad((0, H, 0), (W, H, 0), (W, H, D), (0, H, D))], 0)
walls = add_mesh("walls", [
    quad((0, 0, 0), (W, 0, 0), (W, H, 0), (0, H, 0)),      # back, z = 0, faces +z
    quad((0, 0, 0), (0, H, 0), (0, H, D), (0, 0, D)),      # x = 0, faces +x
    quad((0, 0, D), (0, H, D), (W, H, D), (W, 0, D)),      # front, z = D, faces -z
], 1)
red = add_mesh("red-wall", [quad((W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0))], 3)
# The mezzanine: a 15 cm slab across the back, wall to wall, and its balustrade.
slab = add_mesh("mezzanine", box(0, 2.3, 0, W, 2.45, 1.8), 4)
bars = []
for k in range(11):
    x = 0.3 + 0.54 * k
    bars += box(x, 2.45, 1.72, x + 0.04, 3.45, 1.76)
bars += box(0.1, 3.45, 1.70, W - 0.1, 3.50, 1.78)
balustrade = add_mesh("balustrade", bars, 5)
# Under the mezzanine: a sofa against the back wall and a low table on four legs.
sofa = add_mesh("sofa", box(1.8, 0.0, 0.0, 4.2, 0.45, 0.9) + box(1.8, 0.45, 0.0, 4.2, 0.9, 0.2), 6)
table = box(2.4, 0.38, 1.05, 3.6, 0.42, 1.6)
for (x, z) in [(2.45, 1.1), (3.51, 1.1), (2.45, 1.51), (3.51, 1.51)]:
    table += box(x, 0.0, z, x + 0.04, 0.38, z + 0.04)
low_table = add_mesh("table", table, 7)
# Two tall cabinets against the side walls, each with an uplight 1 cm above its top.
cabinets = add_mesh("cabinets", box(0.0, 0.0, 2.6, 0.45, 2.0, 3.4) + box(W - 0.45, 0.0, 2.6, W, 2.0, 3.4), 7)
lights = add_mesh("uplights", [
    quad((0.05, 2.01, 2.65), (0.05, 2.01, 3.35), (0.4, 2.01, 3.35), (0.4, 2.01, 2.65)),
    quad((W - 0.4, 2.01, 2.65), (W - 0.4, 2.01, 3.35), (W - 0.05, 2.01, 3.35), (W - 0.05, 2.01, 2.65)),
], 8)
ottoman = add_mesh("ottoman", box(-0.3, 0.0, -0.3, 0.3, 0.42, 0.3), 6)

names = ["floor", "ceiling", "walls", "red-wall", "mezzanine", "balustrade", "sofa", "table", "cabinets",
         "uplights"]
nodes = [{"name": n, "mesh": m} for n, m in zip(names, [floor, ceiling, walls, red, slab, balustrade, sofa,
                                                        low_table, cabinets, lights])]
nodes.append({"name": "ottoman", "mesh": ottoman, "translation": [2.2, 0, 3.0], "extras": {"dynamic": True}})
# From the front wall at eye height, looking along -z and 8 degrees up.
nodes.append({"name": "camera", "camera": 0, "translation": [3.0, 1.6, 4.4], "rotation": [0.0698, 0, 0, 0.9976]})
g = {"asset": {"version": "2.0", "generator": "untuned-uplight-room"}, "scene": 0,
     "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
     "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.2, "aspectRatio": 1.333, "znear": 0.05}}],
     "extensionsUsed": ["KHR_materials_emissive_strength"]}
json.dump(g, open(sys.argv[1] if len(sys.argv) > 1 else "uplight-room.gltf", "w"))
