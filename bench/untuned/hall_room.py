"""An untuned closed hall (82 polygons): two ceiling lamps, a column through floor and ceiling, two
overlapping benches, a dynamic cart, and an unlit alcove behind a dynamic sliding panel 3 mm off
the wall.

    python3 bench/untuned/hall_room.py OUT.gltf
    radiosity-cli animate OUT.gltf --object slider --frames 10 --translate 1.8,0,0 --target-fps 60 --compare-full
"""
import json, sys
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, views
mats=[material("plaster", [0.85, 0.83, 0.8]),
 material("steel", [0.4, 0.42, 0.45]),
 material("floor", [0.3, 0.25, 0.2]),
 material("lamp", [0, 0, 0], glow=[1, 0.95, 0.85], strength=8),
 material("green", [0.2, 0.6, 0.3])]
nodes=[]
def obj(name, quads, m, **kw):
    n={"name":name,"mesh":add_mesh(name,quads,m)}; n.update(kw); nodes.append(n)
def boxes(bs): return [q for b in bs for q in box(*b)]
L,H,Wd=9.0,3.2,3.0
obj("floor", box(0,-0.2,0,L,0,Wd), 2)
obj("shell", [q for q in box(0,0,0,L,H,Wd,inward=True) if not all(abs(p[1])<1e-9 for p in q)], 0)   # without its floor face
# an alcove behind the south wall: a box room whose opening a sliding panel closes
obj("alcove", [q for q in box(3,0,-1.5,5,2.4,0,inward=True) if not all(abs(p[2])<1e-9 for p in q)], 0)
obj("slider", boxes([(3.0,0.003,0.01,5.0,2.4,0.05)]), 1, extras={"dynamic":True})
obj("column", boxes([(6.8,-0.3,1.3,7.2,H+0.1,1.7)]), 0)         # through floor and ceiling
obj("bench-a", boxes([(0.5,0,2.3,2.5,0.45,2.8)]), 4)
obj("bench-b", boxes([(2.2,0,2.2,3.6,0.5,2.7)]), 4)               # overlaps bench-a
obj("cart", boxes([(1.0,0.2,0.8,2.0,0.9,1.6),(1.2,0.9,1.0,1.7,1.4,1.4),(1.05,0,0.85,1.15,0.2,0.95),(1.85,0,1.45,1.95,0.2,1.55)]), 1, extras={"dynamic":True})
obj("lamp-1", [[(2.0,H-0.01,1.2),(3.0,H-0.01,1.2),(3.0,H-0.01,1.8),(2.0,H-0.01,1.8)]], 3)
obj("lamp-2", [[(6.0,H-0.01,0.5),(7.0,H-0.01,0.5),(7.0,H-0.01,1.0),(6.0,H-0.01,1.0)]], 3)
nodes.append({"name":"camera","camera":0,"translation":[8.6,1.7,2.6],"rotation":[0,0.54,0,0.84]})
g={"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],"nodes":nodes,"meshes":meshes,"materials":mats,
 "accessors":accessors,"bufferViews":views,"buffers":buffers(),"cameras":[{"type":"perspective","perspective":{"yfov":1.0,"znear":0.05}}],
 "extensionsUsed":["KHR_materials_emissive_strength"]}
json.dump(g,open(sys.argv[1],'w'))
