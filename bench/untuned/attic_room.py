"""An untuned attic: a room under a sloped roof (two slopes meeting at a ridge, gable walls), a
glowing panel 1 cm under one slope (a skylight proxy) facing the roof, its light trapped between
the two (the solve warns `trapped_light`), or with --fix facing into the room; a tessellated
glowing sphere hanging from the ridge, a cylindrical column of 24 faces, a bed turned 30
degrees, a round table (a 16-sided prism) and a chest under the low side.

    python3 bench/untuned/attic_room.py OUT.gltf [--fix]"""
import json, math, sys
sys.path.insert(0, __import__('os').path.dirname(__import__('os').path.abspath(__file__)))
from gltf_writer import material, add_mesh, box, buffers, meshes, accessors, quad, views
materials = [
 material("plaster", [0.78, 0.76, 0.72]),
 material("wood", [0.5, 0.34, 0.2]),
 material("sky", [0, 0, 0], glow=[0.85, 0.9, 1], strength=12),
 material("globe", [0.8, 0.8, 0.8], glow=[1, 0.8, 0.55], strength=25),
 material("linen", [0.7, 0.72, 0.75]),
 material("floor", [0.4, 0.3, 0.22]),
 material("blue", [0.2, 0.3, 0.55]),
]
W, D, Hlow, Hridge = 6.0, 4.0, 1.0, 3.2   # x: 0..W, z: 0..D, ridge along x at z = D/2
zr = D / 2
shell = []
shell.append(quad((0, 0, 0), (W, 0, 0), (W, 0, D), (0, 0, D))[::-1])            # floor faces up
shell.append(quad((0, 0, 0), (0, Hlow, 0), (W, Hlow, 0), (W, 0, 0))[::-1])       # knee wall z=0 faces +z
shell.append(quad((0, 0, D), (W, 0, D), (W, Hlow, D), (0, Hlow, D))[::-1])       # knee wall z=D faces -z
shell.append(quad((0, Hlow, 0), (0, Hridge, zr), (W, Hridge, zr), (W, Hlow, 0)))  # slope A, faces down/+z
shell.append(quad((0, Hlow, D), (W, Hlow, D), (W, Hridge, zr), (0, Hridge, zr)))  # slope B
for x, flip in ((0, False), (W, True)):                                          # gables
    pent = [(x, 0, 0), (x, 0, D), (x, Hlow, D), (x, Hridge, zr), (x, Hlow, 0)]
    if flip: pent = pent[::-1]
    shell.append(pent)
def facing_in(p, c=(W / 2, 1.2, D / 2)):
    a, b, d = p[0], p[1], p[2]
    u = [b[i] - a[i] for i in range(3)]; v = [d[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return p if sum(n[i] * (c[i] - a[i]) for i in range(3)) > 0 else p[::-1]
shell = [facing_in(p) for p in shell]
floor = add_mesh("floor", [shell[0]], 5)
room = add_mesh("room", shell[1:], 0)
# skylight panel 1 cm under slope A, centred at x = 2..3.6, along the slope from t=0.3..0.7
def on_slope(x, t, off):
    y = Hlow + t * (Hridge - Hlow); z = t * zr
    n = (0, zr, -(Hridge - Hlow)); l = math.hypot(*n); n = tuple(c / l for c in n)
    return (x - off * 0 + n[0] * off, y - abs(n[1]) * off, z + n[2] * -off)
L = math.hypot(zr, Hridge - Hlow)
ny, nz = -zr / L, (Hridge - Hlow) / L   # inward normal of slope A (down and toward +z)
def sp(x, t):
    return (x, Hlow + t * (Hridge - Hlow) + 0.01 * ny, t * zr + 0.01 * nz)
sky = add_mesh("skylight", [[sp(2.0, 0.3), sp(2.0, 0.7), sp(3.6, 0.7), sp(3.6, 0.3)][::-1] if "--fix" in sys.argv else [sp(2.0, 0.3), sp(2.0, 0.7), sp(3.6, 0.7), sp(3.6, 0.3)]], 2)
# sphere lamp
def sphere(cx, cy, cz, r, nu=16, nv=10):
    f = []
    for i in range(nv):
        v0, v1 = math.pi * i / nv, math.pi * (i + 1) / nv
        for j in range(nu):
            u0, u1 = 2 * math.pi * j / nu, 2 * math.pi * (j + 1) / nu
            P = lambda u, v: (cx + r * math.sin(v) * math.cos(u), cy + r * math.cos(v), cz + r * math.sin(v) * math.sin(u))
            a, b, c, d = P(u0, v0), P(u1, v0), P(u1, v1), P(u0, v1)
            if i == 0: f.append([a, c, d])
            elif i == nv - 1: f.append([a, b, c])
            else: f.append([a, b, c, d])
    return f
globe = add_mesh("globe", sphere(4.5, 2.3, zr, 0.18), 3)
def prism(cx, cz, r, y0, y1, n):
    f = []
    for k in range(n):
        a0, a1 = 2 * math.pi * k / n, 2 * math.pi * (k + 1) / n
        p0 = (cx + r * math.cos(a0), cz + r * math.sin(a0)); p1 = (cx + r * math.cos(a1), cz + r * math.sin(a1))
        f.append([(p0[0], y0, p0[1]), (p0[0], y1, p0[1]), (p1[0], y1, p1[1]), (p1[0], y0, p1[1])])
    f.append([(cx + r * math.cos(2 * math.pi * k / n), y1, cz + r * math.sin(2 * math.pi * k / n)) for k in range(n)][::-1])
    f.append([(cx + r * math.cos(2 * math.pi * k / n), y0, cz + r * math.sin(2 * math.pi * k / n)) for k in range(n)])
    return f
def fan(poly):  # polygons of more than 4 vertices as triangles
    out = []
    for p in poly:
        if len(p) <= 4: out.append(p)
        else: out += [[p[0], p[k], p[k + 1]] for k in range(1, len(p) - 1)]
    return out
column = add_mesh("column", fan(prism(1.2, zr, 0.15, 0, Hridge, 24)), 0)
table = add_mesh("table", fan(prism(3.2, 2.6, 0.45, 0.7, 0.74, 16) + prism(3.2, 2.6, 0.05, 0, 0.7, 8)), 1)
def rotated(quads, cx, cz, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [[(cx + (x - cx) * c - (z - cz) * s, y, cz + (x - cx) * s + (z - cz) * c) for (x, y, z) in q] for q in quads]
bed = add_mesh("bed", rotated(box(4.0, 0, 0.3, 6.0 - 0.2, 0.45, 1.8), 4.9, 1.05, 30), 4)
chest = add_mesh("chest", box(0.3, 0, 3.2, 1.3, 0.55, 3.75), 6)
nodes = [{"name": n, "mesh": m} for n, m in [("floor", floor), ("room", room), ("skylight", sky), ("globe", globe),
         ("column", column), ("table", table), ("bed", bed), ("chest", chest)]]
nodes.append({"name": "camera", "camera": 0, "translation": [0.4, 1.5, 3.3], "rotation": [-0.02, -0.5, -0.01, 0.866]})
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
     "meshes": meshes, "materials": materials, "accessors": accessors, "bufferViews": views, "buffers": buffers(),
     "cameras": [{"type": "perspective", "perspective": {"yfov": 1.1, "znear": 0.05}}]}
json.dump(g, open(sys.argv[1], 'w'))
