"""A room none of the settings were tuned on, turned 30 degrees about the vertical so that
nothing in it is aligned with the world's axes: an L-shaped plan (a 6 x 3 m room with a
3 x 2.5 m wing), a luminous panel over most of the main room's ceiling and a thin sconce on
the wing's wall (a glowing box flush with the wall: its back face glows out of the room), four
2 cm shelves on a wall with boxes on them, a 16-sided column through floor and ceiling, a flight
of five steps in the wing, and a dynamic armchair (a parent node with child meshes) in front of
the shelves. A camera, turned with the room, looks from the wing's far corner.

    python3 bench/untuned/turned_room.py OUT.gltf
"""
import json
import math
import sys

from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, quad, views

materials = [
    material("plaster", (0.72, 0.70, 0.66)),
    material("oak", (0.55, 0.38, 0.22)),
    material("panel", (0.8, 0.8, 0.8), (1.0, 0.97, 0.9), 3.0),
    material("sconce", (0.8, 0.8, 0.8), (1.0, 0.8, 0.55), 20.0),
    material("fabric", (0.25, 0.4, 0.3)),
    material("stone", (0.45, 0.45, 0.48)),
    material("box-red", (0.6, 0.15, 0.1)),
]
H = 2.8


# The shell of the L: main room x in [0, 6], z in [0, 3]; the wing x in [3, 6], z in [3, 5.5].
# Walls face inward; the wall between room and wing is open over x in [3, 6].
floor = [quad((0, 0, 0), (0, 0, 3), (6, 0, 3), (6, 0, 0)), quad((3, 0, 3), (3, 0, 5.5), (6, 0, 5.5), (6, 0, 3))]
ceiling = [quad((0, H, 0), (6, H, 0), (6, H, 3), (0, H, 3)), quad((3, H, 3), (6, H, 3), (6, H, 5.5), (3, H, 5.5))]
walls = [
    quad((0, 0, 0), (6, 0, 0), (6, H, 0), (0, H, 0)),          # z = 0, faces +z
    quad((0, 0, 0), (0, H, 0), (0, H, 3), (0, 0, 3)),          # x = 0, faces +x
    quad((0, 0, 3), (0, H, 3), (3, H, 3), (3, 0, 3)),          # z = 3 for x in [0, 3], faces -z
    quad((3, 0, 3), (3, H, 3), (3, H, 5.5), (3, 0, 5.5)),      # x = 3 in the wing, faces +x
    quad((3, 0, 5.5), (3, H, 5.5), (6, H, 5.5), (6, 0, 5.5)),  # z = 5.5, faces -z
    quad((6, 0, 0), (6, 0, 5.5), (6, H, 5.5), (6, H, 0)),      # x = 6, faces -x
]
shell = add_mesh("shell", floor + ceiling + walls, 0)
panel = add_mesh("panel", [quad((0.5, H - 0.005, 0.5), (5.5, H - 0.005, 0.5), (5.5, H - 0.005, 2.5), (0.5, H - 0.005, 2.5))], 2)
# A sconce: a thin box on the wing's x = 3 wall, its glowing face toward +x.
sconce = add_mesh("sconce", box(3.0, 1.8, 4.0, 3.04, 1.95, 4.5), 3)
# Four shelves 2 cm thick on the z = 0 wall, x in [0.4, 2.2], 30 cm deep, with a box on each.
shelves = []
for k in range(4):
    y = 0.4 + 0.45 * k
    shelves += box(0.4, y, 0.0, 2.2, y + 0.02, 0.3)
shelf = add_mesh("shelves", shelves, 1)
boxes = []
for k in range(4):
    y = 0.42 + 0.45 * k
    x = 0.6 + 0.35 * k
    boxes += box(x, y, 0.05, x + 0.3, y + 0.25, 0.25)
crates = add_mesh("boxes", boxes, 6)
# A 16-sided column, radius 0.2, at (4.5, 1.5), floor to ceiling (sides only: its ends are buried).
col = []
for k in range(16):
    a0, a1 = 2 * math.pi * k / 16, 2 * math.pi * (k + 1) / 16
    p0 = (4.5 + 0.2 * math.cos(a0), 1.5 + 0.2 * math.sin(a0))
    p1 = (4.5 + 0.2 * math.cos(a1), 1.5 + 0.2 * math.sin(a1))
    col.append(quad((p0[0], 0, p0[1]), (p0[0], H, p0[1]), (p1[0], H, p1[1]), (p1[0], 0, p1[1])))
column = add_mesh("column", col, 5)
# Five steps against the z = 5.5 wall, rising toward +x, each 0.3 m deep and 0.17 m high.
steps = []
for k in range(5):
    x0 = 4.2 + 0.3 * k
    steps += box(x0, 0.0, 4.6, x0 + 0.3, 0.17 * (k + 1), 5.5)
stair = add_mesh("steps", steps, 5)
# The armchair: a seat, a back and two arms, children of one node marked dynamic.
seat = add_mesh("armchair-seat", box(-0.35, 0.2, -0.3, 0.35, 0.42, 0.3), 4)
back = add_mesh("armchair-back", box(-0.35, 0.42, 0.22, 0.35, 0.9, 0.3), 4)
arm = add_mesh("armchair-arm", box(-0.06, 0.2, -0.3, 0.06, 0.6, 0.3), 4)

turn = [0, math.sin(math.radians(15)), 0, math.cos(math.radians(15))]  # 30 degrees about +y
nodes = [
    {"name": "room", "rotation": turn, "children": [1, 2, 3, 4, 5, 6, 7, 8, 13]},
    {"name": "shell", "mesh": shell},
    {"name": "ceiling-panel", "mesh": panel},
    {"name": "sconce", "mesh": sconce},
    {"name": "shelves", "mesh": shelf},
    {"name": "boxes", "mesh": crates},
    {"name": "column", "mesh": column},
    {"name": "steps", "mesh": stair},
    {"name": "armchair", "extras": {"dynamic": True}, "translation": [1.3, 0, 1.4],
     "rotation": [0, 1, 0, 0], "children": [9, 10, 11, 12]},
    {"name": "armchair-seat", "mesh": seat},
    {"name": "armchair-back", "mesh": back},
    {"name": "armchair-arm-left", "mesh": arm, "translation": [-0.35, 0, 0]},
    {"name": "armchair-arm-right", "mesh": arm, "translation": [0.35, 0, 0]},
    {"name": "camera", "camera": 0, "translation": [5.7, 1.7, 5.3],
     "rotation": [-0.0537, 0.3766, 0.0219, 0.9246]},
]
g = {"asset": {"version": "2.0", "generator": "untuned-turned-room"}, "scene": 0,
     "scenes": [{"nodes": [0]}], "nodes": nodes, "meshes": meshes, "materials": materials,
     "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.1, "aspectRatio": 1.333, "znear": 0.05}}],
     "extensionsUsed": ["KHR_materials_emissive_strength"]}
json.dump(g, open(sys.argv[1] if len(sys.argv) > 1 else "turned-room.gltf", "w"))
