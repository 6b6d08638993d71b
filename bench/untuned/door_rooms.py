"""Two rooms joined by a doorway in a 15 cm partition, a dynamic door half open in it, a shelf
passing into a wall, two crates passing into each other, a spot light in one room and a ceiling
panel in the other (59 polygons).

    python3 bench/untuned/door_rooms.py OUT.gltf
    radiosity-cli solve OUT.gltf --report R.json
    radiosity-cli animate OUT.gltf --script bench/untuned/door_rooms_script.json --compare-full
"""
import json, sys, math
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, views
mats=[material("plaster",[0.7,0.68,0.65]), material("wood",[0.55,0.4,0.25]), material("blue",[0.2,0.3,0.6]),
      material("panel",[0,0,0],glow=[1,0.95,0.9],strength=6)]
nodes=[]
def obj(name,q,m,**kw):
    n={"name":name,"mesh":add_mesh(name,q,m)}; n.update(kw); nodes.append(n)
def boxes(bs): return [q for b in bs for q in box(*b)]
H=2.7
obj("shell", box(0,0,0,8,H,4,inward=True), 0)
# the wall between them is the two rooms' walls 15 cm apart; a slab fills the gap but a doorway at z 1.5..2.4
obj("wall", boxes([(4,0,0,4.15,H,1.5),(4,0,2.4,4.15,H,4),(4,2.1,1.5,4.15,H,2.4)]), 0)
# reveals of the doorway (the rooms' walls are single quads over the doorway: cut by the slab? no: left as is)
obj("door", boxes([(-0.02,0,0,0.02,2.08,0.88)]), 1, translation=[4.2,0.005,1.51], rotation=[0,math.sin(-0.5),0,math.cos(-0.5)], extras={"dynamic":True})
obj("shelf", boxes([(0.5,0,-0.1,2.0,1.8,0.35)]), 1)
obj("crate-1", boxes([(5,0,2.5,5.8,0.7,3.3)]), 2)
obj("crate-2", boxes([(5.5,0,2.9,6.2,0.5,3.6)]), 2)
obj("panel", [[(6.0,H-0.01,1.0),(7.0,H-0.01,1.0),(7.0,H-0.01,2.0),(6.0,H-0.01,2.0)]], 3)
nodes.append({"name":"spot","translation":[2,2.4,2],"rotation":[-math.sqrt(0.5),0,0,math.sqrt(0.5)],"extensions":{"KHR_lights_punctual":{"light":0}}})
nodes.append({"name":"camera","camera":0,"translation":[1.0,1.6,3.8],"rotation":[0,0.5,0,0.866]})
g={"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],"nodes":nodes,"meshes":meshes,"materials":mats,
 "accessors":accessors,"bufferViews":views,"buffers":buffers(),"cameras":[{"type":"perspective","perspective":{"yfov":1.0,"znear":0.05}}],
 "extensionsUsed":["KHR_materials_emissive_strength","KHR_lights_punctual"],
 "extensions":{"KHR_lights_punctual":{"lights":[{"type":"spot","intensity":30,"color":[1,1,1],"spot":{"innerConeAngle":0.4,"outerConeAngle":0.8}}]}}}
json.dump(g,open(sys.argv[1],'w'))
