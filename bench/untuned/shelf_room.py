"""A furnished room none of the settings were tuned on: lit only by punctual lights, one of them
a point light 1.5 cm from a wall (a sconce), the other inside an open lampshade of 16 sides whose
material is doubleSided; a bookcase with rows of books 4 mm apart against a wall; a cabinet marked
dynamic; a table on four legs. With --offset D, every node is moved by (D, D/2, -D) metres: the
same room far from the world's origin, as georeferenced building models are. With --site, it stands
on a ground plane 1 km wide, 1 cm under its floor. With --stray D, a 10 cm triangle lies D metres
away along x, as a CAD export's leftover.

    python3 bench/untuned/shelf_room.py OUT.gltf [--offset D] [--site] [--stray D]
"""
import json
import math
import random
import sys

from gltf_writer import accessors, add_mesh, box, buffers, meshes, views

materials=[
 {"name":"plaster","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.78,0.74,1]}},
 {"name":"wood","pbrMetallicRoughness":{"baseColorFactor":[0.5,0.35,0.2,1]}},
 {"name":"shade","pbrMetallicRoughness":{"baseColorFactor":[0.9,0.85,0.7,1]},"doubleSided":True},
 {"name":"red","pbrMetallicRoughness":{"baseColorFactor":[0.6,0.1,0.1,1]}},
 {"name":"floor","pbrMetallicRoughness":{"baseColorFactor":[0.3,0.3,0.32,1]}},
]
W,H,D=4.0,2.6,3.5
walls=box(0,0,0,W,H,D,inward=True)
room=add_mesh("room", [q for i,q in enumerate(walls) if i!=4], 0)
floor=add_mesh("floor", [walls[4]], 4)  # the wall at z = 0, darker
# shade: open cylinder
cyl=[]
n=16;r=0.2;h=0.3
for k in range(n):
    a0=2*math.pi*k/n;a1=2*math.pi*(k+1)/n
    cyl.append([(r*math.cos(a0),0,r*math.sin(a0)),(r*math.cos(a0),h,r*math.sin(a0)),(r*math.cos(a1),h,r*math.sin(a1)),(r*math.cos(a1),0,r*math.sin(a1))])
shade=add_mesh("shade", cyl, 2)
# bookshelf: sides, 5 shelves, back open (against wall at z=D)
sh=[]
sh+=box(0,0,0,0.02,2.0,0.3)
sh+=box(1.2,0,0,1.22,2.0,0.3)
for k in range(6): sh+=box(0.02,k*0.38,0,1.2,k*0.38+0.02,0.3)
shelf=add_mesh("shelf", sh, 1)
books=[]
random.seed(3)
for k in range(5):
    x=0.04
    while x<1.1:
        w=random.uniform(0.02,0.05);hh=random.uniform(0.2,0.33)
        books+=box(x,k*0.38+0.02,0.03,x+w,k*0.38+0.02+hh,0.27)
        x+=w+0.004
bookm=add_mesh("books", books, 3)
cab=add_mesh("cabinet", box(-0.3,0,-0.25,0.3,0.9,0.25), 1)
table=add_mesh("table", box(-0.6,0.72,-0.4,0.6,0.75,0.4)+box(-0.55,0,-0.35,-0.5,0.72,-0.3)+box(0.5,0,-0.35,0.55,0.72,-0.3)+box(-0.55,0,0.3,-0.5,0.72,0.35)+box(0.5,0,0.3,0.55,0.72,0.35), 1)
site=add_mesh("ground", [[(-500,-0.01,-500),(-500,-0.01,500),(500,-0.01,500),(500,-0.01,-500)]], 4) if '--site' in sys.argv else None
nodes=[
 {"name":"room","mesh":room},
 {"name":"floor","mesh":floor},
 {"name":"shade","mesh":shade,"translation":[3.4,1.4,3.0]},
 {"name":"shelf","mesh":shelf,"translation":[0.5,0,D-0.3]},
 {"name":"books","mesh":bookm,"translation":[0.5,0,D-0.3]},
 {"name":"cabinet","mesh":cab,"translation":[2.5,0,0.6],"extras":{"dynamic":True}},
 {"name":"table","mesh":table,"translation":[2.0,0,1.8]},
 {"name":"sconce","extensions":{"KHR_lights_punctual":{"light":0}},"translation":[0.015,1.9,1.5]},
 {"name":"floor-lamp","extensions":{"KHR_lights_punctual":{"light":1}},"translation":[3.4,1.55,3.0]},
 {"name":"camera","camera":0,"translation":[3.7,1.6,0.3],"rotation":[-0.05,0.94,0.15,0.3]},
]
if site is not None: nodes.append({"name":"ground","mesh":site})
if '--stray' in sys.argv:
    far = float(sys.argv[sys.argv.index('--stray') + 1])
    nodes.append({"name":"stray","mesh":add_mesh("stray", [[(far,0,0),(far+0.1,0,0),(far,0.1,0)]], 0)})
g={"asset":{"version":"2.0","generator":"untuned-u5"},"scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],
 "nodes":nodes,"meshes":meshes,"materials":materials,"accessors":accessors,"bufferViews":views,
 "buffers":buffers(),
 "cameras":[{"type":"perspective","perspective":{"yfov":1.0,"aspectRatio":1.5,"znear":0.05}}],
 "extensionsUsed":["KHR_lights_punctual"],
 "extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","color":[1,0.9,0.75],"intensity":3},{"type":"point","color":[1,0.95,0.9],"intensity":5}]}}}
offset = float(sys.argv[sys.argv.index('--offset') + 1]) if '--offset' in sys.argv else 0.0
for n in nodes:
    t = n.get('translation', [0, 0, 0])
    n['translation'] = [t[0] + offset, t[1] + offset / 2, t[2] - offset]
json.dump(g, open(sys.argv[1], 'w'))
