"""A kitchen none of the settings were tuned on, lit only by strips under its wall cupboards:
two glowing strips 3 cm wide face down 1 cm below the cupboards' bottoms, 2 cm from the tiled
wall, over a counter 55 cm below; a third strip runs along a shelf's underside on the side wall.
The light reaches the rest of the room from the counter, the wall and a light floor. An island
with stools stands in the middle, a fridge (a tall box) at the end of the counter, and a window
recess in the back wall with a deep sill. The camera looks from the doorway toward the counter.

    python3 bench/untuned/kitchen_room.py OUT.gltf
"""
import json
import sys

from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, quad, views

materials = [
    material("plaster", (0.75, 0.74, 0.7)),
    material("tiles", (0.55, 0.6, 0.62)),
    material("floor-stone", (0.6, 0.58, 0.52)),
    material("counter", (0.2, 0.2, 0.22)),
    material("cupboard", (0.8, 0.78, 0.72)),
    material("wood", (0.45, 0.3, 0.18)),
    material("steel", (0.6, 0.6, 0.62)),
    material("strip", (0.8, 0.8, 0.8), (1.0, 0.92, 0.8), 25.0),
]
W, D, H = 4.5, 3.6, 2.6


# The shell, facing inward; the back wall z = 0 has a window recess (x 2.9..3.9, y 1.2..2.1,
# 25 cm deep, its far end a dark pane) and is built around it from rectangles.
floor = add_mesh("floor", [quad((0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0))], 2)
ceiling = add_mesh("ceiling", [quad((0, H, 0), (W, H, 0), (W, H, D), (0, H, D))], 0)
wx0, wx1, wy0, wy1, wd = 2.9, 3.9, 1.2, 2.1, 0.25
back = [
    quad((0, 0, 0), (wx0, 0, 0), (wx0, H, 0), (0, H, 0)),
    quad((wx1, 0, 0), (W, 0, 0), (W, H, 0), (wx1, H, 0)),
    quad((wx0, 0, 0), (wx1, 0, 0), (wx1, wy0, 0), (wx0, wy0, 0)),
    quad((wx0, wy1, 0), (wx1, wy1, 0), (wx1, H, 0), (wx0, H, 0)),
    # The recess: sill (faces up), head (faces down), two reveals, and the pane at its end.
    quad((wx0, wy0, 0), (wx1, wy0, 0), (wx1, wy0, -wd), (wx0, wy0, -wd)),
    quad((wx0, wy1, -wd), (wx1, wy1, -wd), (wx1, wy1, 0), (wx0, wy1, 0)),
    quad((wx0, wy0, -wd), (wx0, wy1, -wd), (wx0, wy1, 0), (wx0, wy0, 0)),
    quad((wx1, wy0, 0), (wx1, wy1, 0), (wx1, wy1, -wd), (wx1, wy0, -wd)),
    quad((wx0, wy0, -wd), (wx1, wy0, -wd), (wx1, wy1, -wd), (wx0, wy1, -wd)),
]
walls = add_mesh("walls", back + [
    quad((0, 0, 0), (0, H, 0), (0, H, D), (0, 0, D)),      # x = 0, faces +x
    quad((0, 0, D), (0, H, D), (W, H, D), (W, 0, D)),      # z = D, faces -z
    quad((W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0)),      # x = W, faces -x
], 0)
# Tiles behind the counter: a panel 5 mm in front of the back wall, counter to cupboards.
tiles = add_mesh("backsplash", [quad((0.0, 0.9, 0.005), (2.7, 0.9, 0.005), (2.7, 1.45, 0.005), (0.0, 1.45, 0.005))], 1)
# The base run and its counter along the back wall (x 0..2.7), the wall cupboards above.
counter = add_mesh("counter", box(0.0, 0.0, 0.0, 2.7, 0.86, 0.6) + box(0.0, 0.86, 0.0, 2.72, 0.9, 0.62), 3)
cupboards = add_mesh("wall-cupboards", box(0.0, 1.45, 0.0, 2.7, 2.2, 0.35), 4)
# The strips: under the cupboards, 2 cm from the wall, facing down 1 cm below them.
strips = add_mesh("strips", [
    quad((0.1, 1.44, 0.02), (1.3, 1.44, 0.02), (1.3, 1.44, 0.05), (0.1, 1.44, 0.05)),
    quad((1.4, 1.44, 0.02), (2.6, 1.44, 0.02), (2.6, 1.44, 0.05), (1.4, 1.44, 0.05)),
    # Under a shelf on the x = W wall (the shelf x 4.25..4.5, z 1.0..2.6 at y 1.6).
    quad((4.47, 1.59, 1.1), (4.47, 1.59, 2.5), (4.44, 1.59, 2.5), (4.44, 1.59, 1.1)),
], 7)
shelf = add_mesh("shelf", box(4.25, 1.6, 1.0, W, 1.63, 2.6), 5)
fridge = add_mesh("fridge", box(3.95, 0.0, 0.0, W, 2.0, 0.65), 6)
# The island with two stools (a seat on four legs each).
island = add_mesh("island", box(1.2, 0.0, 1.7, 2.8, 0.9, 2.5), 5)
stool = []
for x0 in (1.5, 2.2):
    stool += box(x0, 0.62, 2.65, x0 + 0.35, 0.66, 3.0)
    for (dx, dz) in ((0, 0), (0.31, 0), (0, 0.31), (0.31, 0.31)):
        stool += box(x0 + dx, 0.0, 2.65 + dz, x0 + dx + 0.04, 0.62, 2.65 + dz + 0.04)
stools = add_mesh("stools", stool, 6)

names = ["floor", "ceiling", "walls", "backsplash", "counter", "wall-cupboards", "strips", "shelf", "fridge",
         "island", "stools"]
mesh_ids = [floor, ceiling, walls, tiles, counter, cupboards, strips, shelf, fridge, island, stools]
nodes = [{"name": n, "mesh": m} for n, m in zip(names, mesh_ids)]
nodes[-1]["extras"] = {"dynamic": True}
# From the doorway corner (x 0.6, z 3.4) at eye height, looking toward the counter and window.
nodes.append({"name": "camera", "camera": 0, "translation": [0.9, 1.6, 3.45],
              "rotation": [-0.0868, -0.2588, -0.0233, 0.9617]})
g = {"asset": {"version": "2.0", "generator": "untuned-kitchen-room"}, "scene": 0,
     "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
     "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.15, "aspectRatio": 1.333, "znear": 0.05}}],
     "extensionsUsed": ["KHR_materials_emissive_strength"]}
json.dump(g, open(sys.argv[1] if len(sys.argv) > 1 else "kitchen-room.gltf", "w"))
