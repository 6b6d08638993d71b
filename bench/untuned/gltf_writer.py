"""What the untuned scene scripts share: indexed-triangle meshes packed into one embedded buffer,
as a modelling tool writes them, and axis-aligned boxes as lists of quads."""
import base64
import struct

pos=[]; idx=[]; meshes=[]; accessors=[]; views=[]
blob=bytearray()
def add_mesh(name, tris_quads, material):
    # tris_quads: list of polygons (3 or 4 verts); emitted as indexed triangles
    v=[]; ind=[]
    for poly in tris_quads:
        base=len(v); v.extend(poly)
        for k in range(1,len(poly)-1): ind += [base, base+k, base+k+1]
    global blob
    while len(blob)%4: blob.append(0)
    vo=len(blob); 
    for p in v: blob += struct.pack('<3f',*p)
    vl=len(blob)-vo
    while len(blob)%4: blob.append(0)
    io=len(blob)
    for i in ind: blob += struct.pack('<H',i)
    il=len(blob)-io
    views.append({"buffer":0,"byteOffset":vo,"byteLength":vl,"target":34962})
    mn=[min(p[c] for p in v) for c in range(3)]; mx=[max(p[c] for p in v) for c in range(3)]
    accessors.append({"bufferView":len(views)-1,"componentType":5126,"count":len(v),"type":"VEC3","min":mn,"max":mx})
    views.append({"buffer":0,"byteOffset":io,"byteLength":il,"target":34963})
    accessors.append({"bufferView":len(views)-1,"componentType":5123,"count":len(ind),"type":"SCALAR"})
    meshes.append({"name":name,"primitives":[{"attributes":{"POSITION":len(accessors)-2},"indices":len(accessors)-1,"material":material}]})
    return len(meshes)-1
def box(x0,y0,z0,x1,y1,z1,inward=False):
    f=[[(x0,y0,z0),(x0,y0,z1),(x0,y1,z1),(x0,y1,z0)],[(x1,y0,z0),(x1,y1,z0),(x1,y1,z1),(x1,y0,z1)],
       [(x0,y0,z0),(x1,y0,z0),(x1,y0,z1),(x0,y0,z1)],[(x0,y1,z0),(x0,y1,z1),(x1,y1,z1),(x1,y1,z0)],
       [(x0,y0,z0),(x0,y1,z0),(x1,y1,z0),(x1,y0,z0)],[(x0,y0,z1),(x1,y0,z1),(x1,y1,z1),(x0,y1,z1)]]
    return [list(reversed(q)) for q in f] if inward else f
def quad(a, b, c, d):
    """A quad's corners, counter-clockwise seen from its front."""
    return [a, b, c, d]
def material(name, colour, glow=None, strength=None):
    """A glTF material of base colour `colour` (RGB); glowing `glow` (RGB) times `strength` when given."""
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(colour) + [1]}}
    if glow is not None:
        m["emissiveFactor"] = list(glow)
        m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
    return m
def buffers():
    """The glTF buffers array: the one buffer, embedded."""
    return [{"byteLength":len(blob),"uri":"data:application/octet-stream;base64,"+base64.b64encode(bytes(blob)).decode()}]
