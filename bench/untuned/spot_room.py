"""A small room none of the settings were tuned on, written as a modelling tool would:
indexed triangles with shared vertices, one mesh instanced by three nodes (one mirrored by a
negative scale), a parent node with child meshes marked dynamic, a spot light, an
emissive_strength ceiling panel, a doubleSided partition, a coincident duplicate quad, a fan
of sliver triangles.

    python3 bench/untuned/spot_room.py OUT.gltf
"""
import json
import math
import sys

from gltf_writer import accessors, add_mesh, box, buffers, meshes, views

materials=[
 {"name":"plaster","pbrMetallicRoughness":{"baseColorFactor":[0.75,0.73,0.7,1]}},
 {"name":"wood","pbrMetallicRoughness":{"baseColorFactor":[0.45,0.3,0.18,1]}},
 {"name":"lamp","emissiveFactor":[1,0.95,0.85],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":6.0}}},
 {"name":"fabric","pbrMetallicRoughness":{"baseColorFactor":[0.2,0.35,0.6,1]},"doubleSided":True},
 {"name":"white"},
]
room=add_mesh("room", box(0,0,0,5,2.8,4,inward=True), 0)
panel=add_mesh("panel", [[(2.0,2.79,1.5),(3.0,2.79,1.5),(3.0,2.79,2.5),(2.0,2.79,2.5)]], 2)
# a stool: reused three times
stool=add_mesh("stool", box(-0.2,0,-0.2,0.2,0.45,0.2), 1)
part=add_mesh("partition", [[(0,0,0),(0,1.6,0),(1.5,1.6,0),(1.5,0,0)]], 3)
dup=add_mesh("rug", [[(1,0.001,1),(1,0.001,2),(2.2,0.001,2),(2.2,0.001,1)],[(1,0.001,1),(1,0.001,2),(2.2,0.001,2),(2.2,0.001,1)]], 4)
fan=[]
for k in range(24):
    a0=k*math.pi/2/24; a1=(k+1)*math.pi/2/24
    fan.append([(4.9,0.5,0.1),(4.9,0.5+2*math.sin(a0),0.1+3.5*math.cos(a0)),(4.9,0.5+2*math.sin(a1),0.1+3.5*math.cos(a1))])
fanm=add_mesh("fan", fan, 4)
seat=add_mesh("seat", box(-0.25,0.42,-0.25,0.25,0.47,0.25), 1)
leg=add_mesh("leg", box(-0.02,0,-0.02,0.02,0.42,0.02), 1)
nodes=[
 {"name":"room","mesh":room},
 {"name":"ceiling-panel","mesh":panel},
 {"name":"stool-a","mesh":stool,"translation":[1.0,0,3.0]},
 {"name":"stool-b","mesh":stool,"translation":[3.5,0,3.0],"rotation":[0,0.3826834,0,0.9238795]},
 {"name":"stool-c","mesh":stool,"translation":[4.0,0,1.0],"scale":[-1,1,1.3]},
 {"name":"partition","mesh":part,"translation":[2.5,0,2.2],"rotation":[0,0.7071068,0,0.7071068]},
 {"name":"rug","mesh":dup},
 {"name":"fan","mesh":fanm},
 {"name":"chair","extras":{"dynamic":True},"translation":[2.0,0,1.0],"children":[9,10,11,12,13]},
 {"name":"chair-seat","mesh":seat},
 {"name":"leg1","mesh":leg,"translation":[-0.2,0,-0.2]},
 {"name":"leg2","mesh":leg,"translation":[0.2,0,-0.2]},
 {"name":"leg3","mesh":leg,"translation":[-0.2,0,0.2]},
 {"name":"leg4","mesh":leg,"translation":[0.2,0,0.2]},
 {"name":"spot","extensions":{"KHR_lights_punctual":{"light":0}},"translation":[0.5,2.6,0.5],"rotation":[-0.3535534,0.3535534,0.1464466,0.8535534]},
 {"name":"camera","camera":0,"translation":[4.6,1.6,3.8],"rotation":[-0.1,0.38,0.04,0.92]},
]
g={"asset":{"version":"2.0","generator":"untuned-u4"},"scene":0,"scenes":[{"nodes":[0,1,2,3,4,5,6,7,8,14,15]}],
 "nodes":nodes,"meshes":meshes,"materials":materials,"accessors":accessors,"bufferViews":views,
 "buffers":buffers(),
 "cameras":[{"type":"perspective","perspective":{"yfov":1.0,"aspectRatio":1.5,"znear":0.05}}],
 "extensionsUsed":["KHR_lights_punctual","KHR_materials_emissive_strength"],
 "extensions":{"KHR_lights_punctual":{"lights":[{"type":"spot","color":[1,0.9,0.7],"intensity":8,"spot":{"innerConeAngle":0.3,"outerConeAngle":0.6}}]}}}
json.dump(g, open(sys.argv[1] if len(sys.argv) > 1 else 'spot-room.gltf', 'w'))
