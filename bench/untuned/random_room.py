"""A random closed room of seed SEED: 2 to 12 boxes, most on the floor, some turned, some
floating, some passing into others, some marked dynamic; one to three lights, each a glowing
panel 0.5 to 50 mm under the ceiling or a KHR_lights_punctual point or spot light; often a
table given as a parent node (marked dynamic) over its legs and top, which touch.

    python3 bench/untuned/random_room.py OUT.gltf SEED
    radiosity-cli solve OUT.gltf --report R.json

Seeds 1 to 20 were tried at the default settings against a quarter of the epsilon, and with
their first dynamic object moved 0.3 m in 3 frames against full solves (README, "Accuracy
against ground truth", random rooms)."""
import json, sys, math, random
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import accessors, add_mesh, box, buffers, material, meshes, views
seed=int(sys.argv[2]); rnd=random.Random(seed)
W,H,D=rnd.uniform(3,9),rnd.uniform(2.3,4),rnd.uniform(3,8)
mats=[material("wall",[rnd.uniform(0.3,0.9)]*3),
      material("red",[rnd.uniform(0.4,0.9),0.1,0.1]),
      material("wood",[0.5,0.35,0.2]),
      material("dark",[0.05,0.05,0.05]),
      material("lamp",[0,0,0],glow=[1,0.9,0.8],strength=rnd.uniform(2,20))]
nodes=[]; roots=[]
def obj(name, quads, m, **kw):
    n={"name":name,"mesh":add_mesh(name,quads,m)}; n.update(kw); nodes.append(n); return len(nodes)-1
roots.append(obj("shell", box(0,0,0,W,H,D,inward=True), 0))
lights=[]
for i in range(rnd.randint(1,3)):
    kind=rnd.choice(["panel","panel","point","spot"])
    x,z=rnd.uniform(0.5,W-0.5),rnd.uniform(0.5,D-0.5)
    if kind=="panel":
        s=rnd.uniform(0.2,1.0); y=H-rnd.choice([0.0005,0.005,0.05])
        roots.append(obj("lamp-%d"%i,[[(x-s/2,y,z-s/2),(x+s/2,y,z-s/2),(x+s/2,y,z+s/2),(x-s/2,y,z+s/2)]],4))
    else:
        lights.append({"type":kind,"intensity":rnd.uniform(5,60),"color":[1,1,1]})
        if kind=="spot": lights[-1]["spot"]={"innerConeAngle":0.3,"outerConeAngle":0.7}
        nodes.append({"name":"plight-%d"%i,"translation":[x,H-0.3,z],"rotation":[-math.sqrt(0.5),0,0,math.sqrt(0.5)],
                      "extensions":{"KHR_lights_punctual":{"light":len(lights)-1}}}); roots.append(len(nodes)-1)
for i in range(rnd.randint(2,12)):
    sx,sy,sz=rnd.uniform(0.1,1.5),rnd.uniform(0.05,1.8),rnd.uniform(0.1,1.5)
    x,z=rnd.uniform(0,W-sx),rnd.uniform(0,D-sz)
    y=0 if rnd.random()<0.7 else rnd.uniform(0,H-sy)
    q=box(-sx/2,0,-sz/2,sx/2,sy,sz/2)
    ang=rnd.choice([0,0,rnd.uniform(0,math.pi)])
    kw={"translation":[x+sx/2,y,z+sz/2],"rotation":[0,math.sin(ang/2),0,math.cos(ang/2)]}
    if rnd.random()<0.3: kw["extras"]={"dynamic":True}
    roots.append(obj("box-%d"%i,q,rnd.randint(0,3),**kw))
# a table as parent + children
if rnd.random()<0.6:
    tx,tz=rnd.uniform(1,W-1),rnd.uniform(1,D-1)
    kids=[obj("leg-%d"%k, box(-0.03,0,-0.03,0.03,0.72,0.03), 2, translation=[dx,0,dz]) for k,(dx,dz) in enumerate([(-0.5,-0.3),(0.5,-0.3),(-0.5,0.3),(0.5,0.3)])]
    top=obj("top", box(-0.55,0.72,-0.35,0.55,0.75,0.35), 2)
    nodes.append({"name":"table","translation":[tx,0,tz],"children":kids+[top],"extras":{"dynamic":True}}); roots.append(len(nodes)-1)
    roots=[r for r in roots if r not in kids+[top]]
nodes.append({"name":"camera","camera":0,"translation":[W*0.5,H*0.6,D-0.1],"rotation":[-0.1,0,0,0.995]}); roots.append(len(nodes)-1)
g={"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":roots}],"nodes":nodes,"meshes":meshes,"materials":mats,
 "accessors":accessors,"bufferViews":views,"buffers":buffers(),"cameras":[{"type":"perspective","perspective":{"yfov":1.0,"znear":0.05}}],
 "extensionsUsed":["KHR_materials_emissive_strength"]+(["KHR_lights_punctual"] if lights else [])}
if lights: g["extensions"]={"KHR_lights_punctual":{"lights":lights}}
json.dump(g,open(sys.argv[1],'w'))
