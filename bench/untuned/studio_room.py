"""An untuned closed studio: a ceiling panel, 25 blind slats 4 cm apart, a rack of 14 plates 8 mm
apart, a sofa of overlapping boxes, a dynamic stool, a dynamic door 5 mm off a doorway into an
unlit closet.

    python3 bench/untuned/studio_room.py OUT.gltf
    radiosity-cli animate OUT.gltf --script bench/untuned/studio_room_script.json --compare-full
"""
import json, sys
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, views
materials=[
 material("wall", [0.75, 0.75, 0.72]),
 material("wood", [0.55, 0.4, 0.25]),
 material("panel", [0.8, 0.8, 0.8], glow=[1, 1, 1], strength=8),
 material("slat", [0.9, 0.9, 0.85]),
 material("plate", [0.85, 0.85, 0.9]),
 material("fabric", [0.3, 0.35, 0.6]),
]
W,H,D=5.0,2.8,4.0
# room with a doorway in the wall x=W into a closet (W..W+1.2, 0..H, 1.0..2.5)
q=lambda *p: [tuple(v) for v in p]
room=[]
room.append(q((0,0,0),(W,0,0),(W,0,D),(0,0,D))[::-1])   # floor facing up
room.append(q((0,H,0),(0,H,D),(W,H,D),(W,H,0))[::-1])   # ceiling facing down
room.append(q((0,0,0),(0,0,D),(0,H,D),(0,H,0))[::-1])   # x=0 wall facing +x
room.append(q((0,0,0),(0,H,0),(W,H,0),(W,0,0))[::-1])   # z=0 facing +z
room.append(q((0,0,D),(W,0,D),(W,H,D),(0,H,D))[::-1])   # z=D facing -z
# x=W wall with a doorway z in [1.5,2.3], y in [0,2.1], facing -x
def wx(z0,z1,y0,y1): return q((W,y0,z0),(W,y1,z0),(W,y1,z1),(W,y0,z1))[::-1]
room+= [wx(0,1.5,0,H), wx(2.3,D,0,H), wx(1.5,2.3,2.1,H)]
roomm=add_mesh("room", room, 0)
closet=add_mesh("closet", [f for f in box(W,0,1.0,W+1.2,H,2.8,inward=True) if not all(abs(v[0]-W)<1e-9 for v in f)], 0)
panel=add_mesh("panel", [q((1.5,H-0.01,1.5),(3.0,H-0.01,1.5),(3.0,H-0.01,2.5),(1.5,H-0.01,2.5))], 2)
blinds=[]
for k in range(25):
    y=0.9+k*0.04
    blinds+=box(1.0,y,0.03,2.6,y+0.002,0.08)
blindm=add_mesh("blinds", blinds, 3)
plates=[]
for k in range(14):
    x=3.4+k*0.012
    plates+=box(x,0.9,0.05,x+0.004,1.14,0.29)
rack=add_mesh("plates", plates+box(3.35,0.88,0.03,3.62,0.9,0.3), 4)
sofa=add_mesh("sofa", box(0.2,0,2.6,2.2,0.45,3.5)+box(0.2,0.3,3.3,2.2,0.9,3.6)+box(0.1,0,2.6,0.4,0.6,3.6)+box(2.0,0,2.6,2.3,0.6,3.6), 5)  # overlapping boxes
door=add_mesh("door", box(-0.005-0.03,0,-0.45,-0.005,2.15,0.45), 1)  # local: door leaf, its face 5 mm off the wall
stool=add_mesh("stool", box(-0.2,0.45,-0.2,0.2,0.5,0.2)+box(-0.18,0,-0.18,-0.14,0.45,-0.14)+box(0.14,0,-0.18,0.18,0.45,-0.14)+box(-0.18,0,0.14,-0.14,0.45,0.18)+box(0.14,0,0.14,0.18,0.45,0.18), 1)
nodes=[
 {"name":"room","mesh":roomm},{"name":"closet","mesh":closet},{"name":"panel","mesh":panel},
 {"name":"blinds","mesh":blindm},{"name":"plates","mesh":rack},{"name":"sofa","mesh":sofa},
 {"name":"door","mesh":door,"translation":[W,0,1.9],"extras":{"dynamic":True}},
 {"name":"stool","mesh":stool,"translation":[3.0,0,2.0],"extras":{"dynamic":True}},
 {"name":"camera","camera":0,"translation":[2.5,1.6,3.9],"rotation":[0,0,0,1]},
]
g={"asset":{"version":"2.0","generator":"untuned-studio"},"scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],
 "nodes":nodes,"meshes":meshes,"materials":materials,"accessors":accessors,"bufferViews":views,"buffers":buffers(),
 "cameras":[{"type":"perspective","perspective":{"yfov":1.0,"aspectRatio":1.5,"znear":0.05}}],
 "extensionsUsed":["KHR_materials_emissive_strength"]}
json.dump(g, open(sys.argv[1],'w'))
