"""An untuned bright room: walls of reflectance 0.85, a large glowing 'window' panel 1 cm off a wall
and facing it (its light trapped between the two: the solve warns `trapped_light`), a hanging box
lamp glowing on every face, a sofa of boxes (marked dynamic), a low table, wall shelves with boxes
on them, a rug 5 mm above the floor.

    python3 bench/untuned/bright_room.py OUT.gltf [--scale S]

--scale S multiplies every coordinate (a model in centimetres: S = 100)."""
import json, sys
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import material, add_mesh, box, buffers, meshes, accessors, views
S = float(sys.argv[sys.argv.index('--scale') + 1]) if '--scale' in sys.argv else 1.0
materials = [
 material("white", [0.85, 0.85, 0.83]),
 material("window", [0, 0, 0], glow=[0.9, 0.95, 1], strength=20),
 material("lamp", [0.8, 0.8, 0.8], glow=[1, 0.85, 0.6], strength=30),
 material("fabric", [0.25, 0.3, 0.5]),
 material("wood", [0.55, 0.38, 0.22]),
 material("rug", [0.6, 0.2, 0.15]),
 material("floor", [0.45, 0.4, 0.35]),
]
def sc(quads): return [[tuple(S * c for c in v) for v in q] for q in quads]
W, H, D = 5.0, 2.7, 4.0
walls = box(0, 0, 0, W, H, D, inward=True)
room = add_mesh("room", sc([q for i, q in enumerate(walls) if i != 2]), 0)
floor = add_mesh("floor", sc([walls[2]]), 6)
window = add_mesh("window", sc([[(0.01, 0.9, 1.0), (0.01, 0.9, 3.0), (0.01, 2.2, 3.0), (0.01, 2.2, 1.0)]]), 1)
lamp = add_mesh("lamp", sc(box(2.35, 2.2, 1.85, 2.65, 2.35, 2.15)), 2)
cord = add_mesh("cord", sc(box(2.49, 2.35, 1.99, 2.51, 2.7, 2.01)), 4)
sofa = add_mesh("sofa", sc(box(1.2, 0, 3.1, 3.4, 0.45, 3.95) + box(1.2, 0.45, 3.7, 3.4, 0.9, 3.95) +
                           box(1.2, 0.45, 3.1, 1.4, 0.65, 3.7) + box(3.2, 0.45, 3.1, 3.4, 0.65, 3.7)), 3)
table = add_mesh("table", sc(box(1.7, 0.38, 1.9, 2.9, 0.42, 2.6) + box(1.75, 0, 1.95, 1.8, 0.38, 2.0) +
                             box(2.8, 0, 1.95, 2.85, 0.38, 2.0) + box(1.75, 0, 2.5, 1.8, 0.38, 2.55) +
                             box(2.8, 0, 2.5, 2.85, 0.38, 2.55)), 4)
shelves = add_mesh("shelves", sc(box(4.7, 1.2, 0.8, 5.0, 1.23, 2.6) + box(4.7, 1.7, 0.8, 5.0, 1.73, 2.6) +
                                 box(4.75, 1.23, 0.9, 4.95, 1.5, 1.2) + box(4.75, 1.23, 1.6, 4.95, 1.4, 2.3) +
                                 box(4.75, 1.73, 1.0, 4.95, 2.0, 1.5)), 4)
rug = add_mesh("rug", sc([[(1.3, 0.005, 1.5), (1.3, 0.005, 3.0), (3.3, 0.005, 3.0), (3.3, 0.005, 1.5)]]), 5)
nodes = [{"name": n, "mesh": m} for n, m in [("room", room), ("floor", floor), ("window", window), ("lamp", lamp),
         ("cord", cord), ("sofa", sofa), ("table", table), ("shelves", shelves), ("rug", rug)]]
nodes[5]["extras"] = {"dynamic": True}
nodes.append({"name": "camera", "camera": 0, "translation": [4.6 * S, 1.5 * S, 0.4 * S],
              "rotation": [-0.06, 0.92, 0.15, 0.36]})
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
     "meshes": meshes, "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.05, "znear": 0.05 * S}}]}
json.dump(g, open(sys.argv[1], 'w'))
