"""A room with things laid flush on its surfaces, none of the settings tuned on it: a 4 x 2.6 x 3.5 m
room, a ceiling lamp panel listed after the room, a poster on the back wall and a rug on the floor
(each listed after the surface it lies on), and a panel listed before the wall it lies on.

    python3 bench/untuned/flush_room.py OUT.gltf [--off D] [--lamp-gap G] [--flipped]

--off D lifts the poster, panel and rug D metres off their surfaces; the lamp hangs G metres under
the ceiling (G = D unless given); --flipped turns the lamp to face the ceiling (its normal flipped,
the light trapped between the two: the solve warns `trapped_light`)."""
import json, sys
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import material, add_mesh, box, buffers, meshes, accessors, views
off = float(sys.argv[sys.argv.index('--off') + 1]) if '--off' in sys.argv else 0.0
gap = float(sys.argv[sys.argv.index('--lamp-gap') + 1]) if '--lamp-gap' in sys.argv else off
materials = [
 material("plaster", [0.8, 0.78, 0.74]),
 material("red", [0.7, 0.15, 0.1]),
 material("blue", [0.15, 0.25, 0.7]),
 material("lamp", [0, 0, 0], glow=[1, 1, 1], strength=8),
 material("green", [0.2, 0.6, 0.25]),
]
W, H, D = 4.0, 2.6, 3.5
walls = box(0, 0, 0, W, H, D, inward=True)
panel = add_mesh("panel", [[(0.6, 0.8, off), (0.6, 1.8, off), (1.6, 1.8, off), (1.6, 0.8, off)][::-1]], 4)
room = add_mesh("room", walls, 0)
poster = add_mesh("poster", [[(2.2, 0.9, off), (2.2, 1.9, off), (3.2, 1.9, off), (3.2, 0.9, off)][::-1]], 1)
rug = add_mesh("rug", [[(1.0, off, 1.2), (1.0, off, 2.6), (3.0, off, 2.6), (3.0, off, 1.2)]], 2)
lamp_quad = [(1.6, H - gap, 1.4), (2.4, H - gap, 1.4), (2.4, H - gap, 2.1), (1.6, H - gap, 2.1)]
lamp = add_mesh("lamp", [lamp_quad[::-1] if '--flipped' in sys.argv else lamp_quad], 3)
nodes = [{"name": "panel", "mesh": panel}, {"name": "room", "mesh": room}, {"name": "poster", "mesh": poster},
         {"name": "rug", "mesh": rug}, {"name": "lamp", "mesh": lamp},
         {"name": "camera", "camera": 0, "translation": [2.0, 1.4, 3.4]}]
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
     "meshes": meshes, "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.1, "znear": 0.05}}]}
json.dump(g, open(sys.argv[1], 'w'))
