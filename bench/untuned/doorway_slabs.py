"""A room none of the settings were tuned on, for trying the import's cuts with a door and
overlapping geometry: slab floor and roof, outer walls through them, an inner wall with a doorway
(three boxes in one mesh) and a dynamic door in it, a doubleSided screen of no thickness standing on
the slab, a rug 1 mm above the floor, a table whose legs sink 2 cm into the slab placed twice in
place, a shelf sunk into a wall, a dynamic chair, a glowing panel and a spot light.

    python3 bench/untuned/doorway_slabs.py OUT.gltf
    radiosity-cli animate OUT.gltf --script bench/untuned/doorway_slabs_script.json --compare-full --report a.json
"""
import json, sys
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import accessors, add_mesh, box, buffers, meshes, views
mats=[{"name":"wall","pbrMetallicRoughness":{"baseColorFactor":[0.7,0.72,0.75,1]}},
 {"name":"wood","pbrMetallicRoughness":{"baseColorFactor":[0.55,0.4,0.25,1]}},
 {"name":"rug","pbrMetallicRoughness":{"baseColorFactor":[0.6,0.15,0.1,1]}},
 {"name":"lamp","pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1]},"emissiveFactor":[1,1,0.9],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":6}}},
 {"name":"board","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.8,0.8,1]},"doubleSided":True}]
nodes=[]
def obj(name, quads, m, **kw):
    n={"name":name,"mesh":add_mesh(name,quads,m)}; n.update(kw); nodes.append(n)
def boxes(bs): return [q for b in bs for q in box(*b)]
W,H,D,T=7.0,2.8,5.0,0.25
obj("slab", boxes([(-T,-T,-T,W+T,0,D+T)]), 0)
obj("roof", boxes([(-T,H,-T,W+T,H+T,D+T)]), 0)
obj("walls", boxes([(-T,-0.1,-T,W+T,H+0.1,0),(-T,-0.1,D,W+T,H+0.1,D+T),(-T,-0.1,0,0,H+0.1,D),(W,-0.1,0,W+T,H+0.1,D)]), 0)
# wall with doorway at x=4 (three boxes, one mesh), door dynamic in it
obj("inner-wall", boxes([(4,-0.1,-0.05,4.15,H+0.1,2.0),(4,2.05,2.0,4.15,H+0.1,2.9),(4,-0.1,2.9,4.15,H+0.1,D+0.05)]), 0)
obj("door", boxes([(4.03,0.005,2.0,4.12,2.04,2.9)]), 1, extras={"dynamic":True})
# thin partition in the west part, standing on the slab, half depth
obj("screen", [[(2,0,0),(2,0,2.5),(2,2.2,2.5),(2,2.2,0)]], 4)
obj("rug", [[(0.5,0.001,3),(0.5,0.001,4.5),(3.5,0.001,4.5),(3.5,0.001,3)]], 2)
tbl=boxes([(0.8,0.7,0.6,1.8,0.74,1.4),(0.85,-0.02,0.65,0.9,0.7,0.7),(1.7,-0.02,0.65,1.75,0.7,0.7),(0.85,-0.02,1.3,0.9,0.7,1.35),(1.7,-0.02,1.3,1.75,0.7,1.35)])
obj("table", tbl, 1); obj("table-copy", tbl, 1)
obj("shelf", boxes([(5.0,0,D-0.3,6.5,1.8,D+0.05)]), 1)
obj("chair", boxes([(5.5,0,1,6,0.45,1.5),(5.5,0.45,1.45,6,1.0,1.5)]), 1, extras={"dynamic":True})
obj("panel", [[(1.0,H-0.01,3.2),(2.0,H-0.01,3.2),(2.0,H-0.01,3.8),(1.0,H-0.01,3.8)]], 3)
nodes.append({"name":"spot","translation":[5.5,2.6,3.0],"rotation":[-0.7071,0,0,0.7071],"extensions":{"KHR_lights_punctual":{"light":0}}})
nodes.append({"name":"camera","camera":0,"translation":[6.6,1.6,4.6],"rotation":[0,0.42,0,0.907]})
g={"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],"nodes":nodes,"meshes":meshes,"materials":mats,
 "accessors":accessors,"bufferViews":views,"buffers":buffers(),"cameras":[{"type":"perspective","perspective":{"yfov":1.0,"znear":0.05}}],
 "extensionsUsed":["KHR_lights_punctual","KHR_materials_emissive_strength"],
 "extensions":{"KHR_lights_punctual":{"lights":[{"type":"spot","color":[1,0.9,0.8],"intensity":4,"spot":{"innerConeAngle":0.3,"outerConeAngle":0.7}}]}}}
json.dump(g,open(sys.argv[1],'w'))
