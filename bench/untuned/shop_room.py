"""An untuned closed shop (77 polygons): a lamp panel, an unlit store cupboard behind a dynamic
sliding door 2 cm off its wall, two intersecting crates, a rack sunk 4 cm into the wall, a mat
given twice, a dynamic trolley.

    python3 bench/untuned/shop_room.py OUT.gltf
    radiosity-cli animate OUT.gltf --script bench/untuned/shop_room_script.json --compare-full
"""
import json, sys
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, views
mats=[material("plaster", [0.75, 0.7, 0.65]),
 material("metal", [0.4, 0.45, 0.5]),
 material("crate", [0.6, 0.5, 0.3]),
 material("lamp", [0, 0, 0], glow=[1, 0.95, 0.85], strength=8)]
nodes=[]
def obj(name, quads, m, **kw):
    n={"name":name,"mesh":add_mesh(name,quads,m)}; n.update(kw); nodes.append(n)
def boxes(bs): return [q for b in bs for q in box(*b)]
W,H,D=6.0,2.6,3.2
# shop room, closed, faces inward
obj("shell", box(0,0,0,W,H,D,inward=True), 0)
# a store cupboard in the corner: walls of slabs, opening at z 1.0..1.9 on its x=4.5 side, unlit
obj("store", boxes([(4.5,0,0,4.6,H,1.0),(4.5,0,1.9,4.6,H,D),(4.5,2.1,1.0,4.6,H,1.9)]), 0)
obj("store-door", boxes([(4.42,0.003,0.95,4.48,2.09,1.95)]), 1, extras={"dynamic":True})
# two crates that intersect, and a rack sunk 4 cm into the back wall
obj("crate-a", boxes([(0.5,0,0.4,1.3,0.8,1.2)]), 2)
obj("crate-b", boxes([(1.0,0,0.9,1.7,0.6,1.6)]), 2)
obj("rack", boxes([(2.0,0,-0.04,3.8,1.9,0.45)]), 1)
# a floor mat given twice, on top of each other
mat=[[(0.5,0.002,2.0),(0.5,0.002,2.9),(2.5,0.002,2.9),(2.5,0.002,2.0)]]
obj("mat", mat, 2); obj("mat-again", mat, 2)
obj("trolley", boxes([(2.6,0.1,1.6,3.4,0.9,2.2),(2.65,0,1.65,2.7,0.1,1.7),(3.3,0,2.1,3.35,0.1,2.15)]), 1, extras={"dynamic":True})
obj("lamp", [[(1.5,H-0.005,1.2),(2.7,H-0.005,1.2),(2.7,H-0.005,2.0),(1.5,H-0.005,2.0)]], 3)
nodes.append({"name":"camera","camera":0,"translation":[0.3,1.6,3.0],"rotation":[0,-0.5,0,0.866]})
g={"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],"nodes":nodes,"meshes":meshes,"materials":mats,
 "accessors":accessors,"bufferViews":views,"buffers":buffers(),"cameras":[{"type":"perspective","perspective":{"yfov":1.0,"znear":0.05}}],
 "extensionsUsed":["KHR_materials_emissive_strength"]}
json.dump(g,open(sys.argv[1],'w'))
