"""A room as a Blender user makes it, written by Blender's own glTF exporter with its defaults
(every material doubleSided, custom properties as extras, a parent empty with child meshes, a
smooth UV sphere, a turned and scaled box, a point light in watts, a camera). None of the
settings were tuned on it. Needs Debian's blender and python3-numpy (the exporter imports it):

    blender --background --factory-startup --python bench/untuned/blender_room.py -- OUT.gltf

`bench/untuned/blender-room.glb` is its output (OUT ending in .glb: one binary file), kept with
its Cycles reference (bench/references/blender-room.*, bench/cycles/README.md). The exporter is
not byte for byte repeatable (the vertex data differs in its last bits between runs): the kept
file is the one the reference was rendered from.
"""
import bpy, math, sys
argv = sys.argv[sys.argv.index("--") + 1:]
out = argv[0]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene

def material(name, color, emission=None, strength=1.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    b = m.node_tree.nodes["Principled BSDF"]
    b.inputs["Base Color"].default_value = (*color, 1.0)
    b.inputs["Roughness"].default_value = 1.0
    if emission:
        b.inputs["Emission"].default_value = (*emission, 1.0)
        b.inputs["Emission Strength"].default_value = strength
    return m

white = material("white", (0.8, 0.8, 0.8))
red = material("red", (0.7, 0.1, 0.1))
wood = material("wood", (0.5, 0.3, 0.15))
lamp = material("lamp", (0, 0, 0), (1.0, 0.95, 0.85), 20.0)

# The room: a cube 6 x 4 x 3 (Blender Z up), its normals flipped inward.
bpy.ops.mesh.primitive_cube_add(size=1, location=(0, 0, 1.5))
room = bpy.context.object
room.name = "room"
room.scale = (6, 4, 3)
bpy.ops.object.transform_apply(scale=True)
bpy.ops.object.mode_set(mode="EDIT")
bpy.ops.mesh.select_all(action="SELECT")
bpy.ops.mesh.flip_normals()
bpy.ops.object.mode_set(mode="OBJECT")
room.data.materials.append(white)

# A ceiling panel that glows.
bpy.ops.mesh.primitive_plane_add(size=1, location=(0, 0, 2.99))
panel = bpy.context.object
panel.name = "ceiling-light"
panel.scale = (1.2, 0.6, 1)
panel.rotation_euler = (math.pi, 0, 0)  # facing down
panel.data.materials.append(lamp)

# A table: an empty parent with a top and four legs, marked dynamic.
bpy.ops.object.empty_add(location=(1.0, 0.5, 0))
table = bpy.context.object
table.name = "table"
table["dynamic"] = True
def child_box(name, loc, scale, mat, parent):
    bpy.ops.mesh.primitive_cube_add(size=1, location=loc)
    o = bpy.context.object
    o.name = name
    o.scale = scale
    o.data.materials.append(mat)
    o.parent = parent
    o.matrix_parent_inverse = parent.matrix_world.inverted()
    return o
child_box("table-top", (1.0, 0.5, 0.72), (1.4, 0.8, 0.04), wood, table)
for i, (dx, dy) in enumerate([(-0.65, -0.35), (0.65, -0.35), (-0.65, 0.35), (0.65, 0.35)]):
    child_box(f"table-leg-{i}", (1.0 + dx, 0.5 + dy, 0.35), (0.05, 0.05, 0.7), wood, table)

# A ball on the floor (smooth shading, many quads and triangles).
bpy.ops.mesh.primitive_uv_sphere_add(radius=0.3, location=(-1.5, -0.8, 0.3), segments=24, ring_count=12)
ball = bpy.context.object
ball.name = "ball"
bpy.ops.object.shade_smooth()
ball.data.materials.append(red)
ball["dynamic"] = True

# A rotated, non-uniformly scaled box.
bpy.ops.mesh.primitive_cube_add(size=1, location=(-2.0, 1.2, 0.5), rotation=(0, 0, math.radians(30)))
cab = bpy.context.object
cab.name = "cabinet"
cab.scale = (0.8, 0.5, 1.0)
cab.data.materials.append(wood)

# A point light (W) and a camera.
bpy.ops.object.light_add(type="POINT", location=(-1.5, 1.0, 2.2))
bpy.context.object.name = "bulb"
bpy.context.object.data.energy = 100.0
bpy.ops.object.camera_add(location=(2.6, -1.7, 1.6))
cam = bpy.context.object
cam.name = "camera"
cam.rotation_euler = (math.radians(78), 0, math.radians(55))
scene.camera = cam

bpy.ops.export_scene.gltf(filepath=out, export_format="GLB" if out.endswith(".glb") else "GLTF_SEPARATE",
                          export_cameras=True, export_lights=True, export_extras=True)
