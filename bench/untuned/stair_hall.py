"""Two floors none of the settings were tuned on, joined by a stair through an opening in the
slab between them: the upper floor is lit by a ceiling panel, the lower floor only through the
opening (2 x 1.2 m), by light that bounces off white walls (reflectance 0.85) and down the
stair. The lower floor holds a sofa and a low table; a railing of thin bars guards the opening
upstairs. The camera stands on the lower floor and looks toward the stair and the opening.

    python3 bench/untuned/stair_hall.py OUT.gltf
"""
import json
import sys

from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, quad, views

materials = [
    material("white", (0.85, 0.85, 0.83)),
    material("oak", (0.5, 0.38, 0.25)),
    material("stone", (0.6, 0.58, 0.55)),
    material("grey-fabric", (0.35, 0.36, 0.4)),
    material("steel", (0.4, 0.4, 0.42)),
    material("panel", (0.8, 0.8, 0.8), (1.0, 0.96, 0.9), 6.0),
]
W, D = 6.0, 4.0
H0, S, H1 = 2.8, 0.2, 2.8          # lower storey, slab, upper storey
Y1 = H0 + S                          # upper floor level
TOP = Y1 + H1
ox0, ox1, oz0, oz1 = 3.6, 5.6, 0.4, 1.6   # the opening in the slab

# Lower storey: floor, walls (facing in) and the slab's underside around the opening.
lower_floor = add_mesh("lower-floor", [quad((0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0))], 1)
def walls_between(y0, y1):
    return [quad((0, y0, 0), (W, y0, 0), (W, y1, 0), (0, y1, 0)),
            quad((0, y0, 0), (0, y1, 0), (0, y1, D), (0, y0, D)),
            quad((0, y0, D), (0, y1, D), (W, y1, D), (W, y0, D)),
            quad((W, y0, 0), (W, y0, D), (W, y1, D), (W, y1, 0))]
# The slab around the opening as four boxes (its underside faces down, its top up, its edges line the opening).
slab = (box(0, H0, 0, ox0, Y1, D) + box(ox1, H0, 0, W, Y1, D) + box(ox0, H0, 0, ox1, Y1, oz0) +
        box(ox0, H0, oz1, ox1, Y1, D))
walls = add_mesh("walls", walls_between(0, H0) + walls_between(Y1, TOP) +
                 [quad((0, TOP, 0), (W, TOP, 0), (W, TOP, D), (0, TOP, D))], 0)
slab_mesh = add_mesh("slab", slab, 2)
# The stair: 14 solid steps along +x under the opening, from the lower floor to the upper one.
steps = []
n = 14
x_start = ox1 - n * 0.28
for k in range(n):
    x0 = x_start + 0.28 * k
    steps += box(x0, 0.0, oz0, x0 + 0.28, Y1 * (k + 1) / n, oz1)
stair = add_mesh("stair", steps, 2)
# Upstairs: a railing of 4 cm bars along the opening's long side (z = oz1), and the panel.
rail = []
for k in range(8):
    x = ox0 + 0.1 + k * 0.26
    rail += box(x, Y1, oz1 + 0.02, x + 0.04, Y1 + 0.9, oz1 + 0.06)
rail += box(ox0, Y1 + 0.9, oz1 + 0.01, ox1, Y1 + 0.95, oz1 + 0.07)
railing = add_mesh("railing", rail, 4)
panel = add_mesh("panel", [quad((1.0, TOP - 0.01, 1.2), (2.6, TOP - 0.01, 1.2), (2.6, TOP - 0.01, 2.8), (1.0, TOP - 0.01, 2.8))], 5)
# Downstairs: a sofa against the z = D wall and a low table.
sofa = add_mesh("sofa", box(0.6, 0.0, 3.1, 2.6, 0.42, 4.0) + box(0.6, 0.42, 3.8, 2.6, 0.85, 4.0), 3)
table = add_mesh("table", box(1.1, 0.0, 2.2, 2.1, 0.4, 2.8), 1)

names = ["lower-floor", "walls", "slab", "stair", "railing", "panel", "sofa", "table"]
ids = [lower_floor, walls, slab_mesh, stair, railing, panel, sofa, table]
nodes = [{"name": nm, "mesh": m} for nm, m in zip(names, ids)]
# On the lower floor by the x = 0 wall, looking along +x and up toward the opening.
nodes.append({"name": "camera", "camera": 0, "translation": [0.3, 1.5, 2.6],
              "rotation": [0.1167, -0.6974, 0.1167, 0.6974]})
g = {"asset": {"version": "2.0", "generator": "untuned-stair-hall"}, "scene": 0,
     "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
     "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.2, "aspectRatio": 1.333, "znear": 0.05}}],
     "extensionsUsed": ["KHR_materials_emissive_strength"]}
json.dump(g, open(sys.argv[1] if len(sys.argv) > 1 else "stair-hall.gltf", "w"))
