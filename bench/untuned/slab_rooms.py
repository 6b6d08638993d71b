"""Two rooms built as a modeller builds them from slabs: one floor slab and one ceiling slab under
and over both rooms, outer walls that run through the slabs and each other at the corners, and a
partition slab that runs 10 cm into the floor, the ceiling and the outer walls. Only the west room
has a light (a glowing ceiling panel). Without --doorway the partition is whole, so no straight
line joins the rooms and every surface of the east room must stay black: whatever light it gets
leaked. With --doorway the partition has a doorway 0.9 m wide and 2.1 m high. With --touching
the partition only touches the slabs and walls (as a wall drawn standing on the floor); with
--thin it is one doubleSided quad (no thickness) touching them. None of the settings were tuned
on it.

    python3 bench/untuned/slab_rooms.py OUT.gltf [--doorway | --thin] [--touching]
"""
import json
import sys

from gltf_writer import accessors, add_mesh, box, buffers, meshes, views

materials = [
    {"name": "plaster", "pbrMetallicRoughness": {"baseColorFactor": [0.78, 0.76, 0.72, 1]}},
    {"name": "oak", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.32, 0.2, 1]}},
    {"name": "lamp", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]},
     "emissiveFactor": [1, 0.95, 0.85], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}},
    {"name": "screed", "pbrMetallicRoughness": {"baseColorFactor": [0.35, 0.34, 0.33, 1]}},
]
L, H, D, T = 8.2, 2.7, 4.0, 0.2  # both rooms' length along x, height, depth; slab thickness
X = 4.0  # the partition's west face
nodes = []


def slab(name, boxes, material, dynamic=False):
    node = {"name": name, "mesh": add_mesh(name, [q for b in boxes for q in box(*b)], material)}
    if dynamic:
        node["extras"] = {"dynamic": True}
    nodes.append(node)


slab("floor-slab", [(-T, -T, -T, L + T, 0, D + T)], 3)
slab("ceiling-slab", [(-T, H, -T, L + T, H + T, D + T)], 0)
slab("south-wall", [(-T, -T, -T, L + T, H + T, 0)], 0)
slab("north-wall", [(-T, -T, D, L + T, H + T, D + T)], 0)
slab("west-wall", [(-T, -T, -T, 0, H + T, D + T)], 0)
slab("east-wall", [(L, -T, -T, L + T, H + T, D + T)], 0)
S = 0.0 if "--touching" in sys.argv or "--thin" in sys.argv else 0.1  # how far the partition runs into the slabs and walls
if "--thin" in sys.argv:
    materials.append({"name": "board", "pbrMetallicRoughness": {"baseColorFactor": [0.78, 0.76, 0.72, 1]},
                      "doubleSided": True})
    nodes.append({"name": "partition", "mesh": add_mesh("partition", [[(X, 0, 0), (X, 0, D), (X, H, D), (X, H, 0)]],
                                                          len(materials) - 1)})
elif "--doorway" in sys.argv:
    slab("partition", [(X, -S, -S, X + T, H + S, 1.5), (X, 2.1, 1.5, X + T, H + S, 2.4),
                       (X, -S, 2.4, X + T, H + S, D + S)], 0)
else:
    slab("partition", [(X, -S, -S, X + T, H + S, D + S)], 0)
# The lit room: a glowing panel just under the ceiling, a table, a cabinet against the partition.
nodes.append({"name": "ceiling-light",
              "mesh": add_mesh("ceiling-light", [[(1.4, H - 0.01, 1.7), (2.6, H - 0.01, 1.7),
                                                  (2.6, H - 0.01, 2.3), (1.4, H - 0.01, 2.3)]], 2)})
slab("table", [(1.2, 0.72, 0.8, 2.4, 0.76, 1.6), (1.25, 0, 0.85, 1.3, 0.72, 0.9), (2.3, 0, 0.85, 2.35, 0.72, 0.9),
               (1.25, 0, 1.5, 1.3, 0.72, 1.55), (2.3, 0, 1.5, 2.35, 0.72, 1.55)], 1, dynamic=True)
slab("west-cabinet", [(X - 0.5, 0, 2.6, X - 0.02, 1.2, 3.6)], 1)
# The dark room: a cabinet sunk 5 cm into the partition, a bench, a crate on the floor.
slab("east-cabinet", [(X + T - 0.05, 0, 0.4, X + T + 0.5, 1.2, 1.2)], 1)
slab("bench", [(6.0, 0.4, 2.6, 7.6, 0.45, 3.2), (6.05, 0, 2.65, 6.15, 0.4, 3.15), (7.45, 0, 2.65, 7.55, 0.4, 3.15)], 1)
slab("crate", [(6.5, 0, 0.8, 7.1, 0.6, 1.4)], 1)
nodes.append({"name": "camera", "camera": 0, "translation": [L - 0.3, 1.6, D - 0.4],
              "rotation": [0.0, 0.3827, 0.0, 0.9239]})  # in the east room, looking toward the partition
g = {"asset": {"version": "2.0", "generator": "untuned-slab-rooms"}, "scene": 0,
     "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
     "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.1, "aspectRatio": 1.5, "znear": 0.05}}],
     "extensionsUsed": ["KHR_materials_emissive_strength"]}
json.dump(g, open(sys.argv[1], "w"))
