"""Render a path-traced reference image of a scene with Blender Cycles.

    blender -b --factory-startup --python bench/cycles/render_reference.py -- \
        SCENE.gltf OUT_PREFIX [--size WxH] [--samples N] [--seed S]

Writes
    OUT_PREFIX.pfm          linear RGB radiosity B per pixel (W/m^2), background 0
    OUT_PREFIX-lights.pfm   1 where the pixel centre sees the front of a light source
                            (a surface with emission > 0), else 0
    OUT_PREFIX.json         how it was made: command, Blender version, samples, seed,
                            size, render seconds, scene checksum

The render follows the engine's conventions so the two images compare directly:
- Camera: the glTF camera (position, orientation, yfov), vertical sensor fit, so the
  vertical field of view is yfov whatever the image aspect (the engine does the same:
  the image decides the aspect).
- Materials: every surface is Lambertian with reflectance = baseColorFactor, and emits
  E = emissiveFactor x KHR_materials_emissive_strength. Cycles shows an Emission shader of
  strength S as the pixel value S, i.e. its radiances are pi times physical ones, so an
  emitter reads E and a diffuse surface reads pi L = B, the engine's radiosity.
- One-sided polygons: the back of every face (Backfacing) is black and emits nothing.
- Film: black world, Standard view transform, no denoising, no adaptive sampling, no
  clamping, 128 diffuse bounces. Pixel filter: a Gaussian of width 0.01, Cycles' smallest
  (every sample within 0.015 px of the pixel centre), so each pixel is the point at its
  centre like the engine's rasteriser (no multisampling). Cycles' Box filter would not do:
  it is always 1 px wide, an area average, whatever its width says.
- PFM: little-endian ("PF", scale -1), rows bottom to top, as app/image/Image.cpp writes.

Only the Python standard library and bpy are used.
"""

import argparse
import array
import hashlib
import json
import math
import os
import struct
import sys
import tempfile
import time

import bpy


def parse_args():
    argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    ap = argparse.ArgumentParser(prog='render_reference.py',
                                 description='Cycles reference image of a glTF scene (see the module docstring).')
    ap.add_argument('scene', help='glTF 2.0 scene with one camera')
    ap.add_argument('out_prefix', help='writes OUT_PREFIX.pfm, OUT_PREFIX-lights.pfm, OUT_PREFIX.json')
    ap.add_argument('--size', default='128x128', help='WxH in pixels (default 128x128)')
    ap.add_argument('--samples', type=int, default=1024, help='samples per pixel (default 1024)')
    ap.add_argument('--seed', type=int, default=0, help='Cycles seed (default 0)')
    args = ap.parse_args(argv)
    w, h = args.size.lower().split('x')
    args.width, args.height = int(w), int(h)
    if args.width < 1 or args.height < 1 or args.samples < 1:
        ap.error('size and samples must be positive')
    return args


def read_gltf_json(path):
    with open(path, 'rb') as f:
        data = f.read()
    if data[:4] == b'glTF':  # binary container: the JSON chunk follows the 12-byte header
        length = struct.unpack_from('<I', data, 12)[0]
        return json.loads(data[20:20 + length].decode('utf-8')), data
    return json.loads(data.decode('utf-8')), data


def fnv1a64(data):
    """64-bit FNV-1a of the scene file: the tests recompute it to catch a stale reference."""
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return '%016x' % h


def clear_scene():
    """--factory-startup brings a cube, a lamp and a camera: remove them and their data."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
        for block in list(coll):
            coll.remove(block)


LIGHT_AOV = 'light'


def lambertian_material(name, reflectance, emission, double_sided=False):
    """Front: Diffuse(reflectance) + Emission(emission, strength 1). Back: black diffuse, or
    the same as the front for a doubleSided material (the engine gives it a back face of its
    own). An emitter also writes 1 - Backfacing (1 if doubleSided) to the 'light' AOV: averaged
    over a pixel's camera samples it is the fraction of them that see a light's front, which
    makes the light mask."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new('ShaderNodeOutputMaterial')
    out.target = 'CYCLES'

    diffuse = nodes.new('ShaderNodeBsdfDiffuse')
    diffuse.inputs['Color'].default_value = (*reflectance, 1.0)
    diffuse.inputs['Roughness'].default_value = 0.0  # Lambert, not Oren-Nayar
    front = diffuse.outputs['BSDF']
    geometry = nodes.new('ShaderNodeNewGeometry')
    if any(c > 0.0 for c in emission):
        emit = nodes.new('ShaderNodeEmission')
        emit.inputs['Color'].default_value = (*emission, 1.0)
        emit.inputs['Strength'].default_value = 1.0
        both = nodes.new('ShaderNodeAddShader')
        links.new(diffuse.outputs['BSDF'], both.inputs[0])
        links.new(emit.outputs['Emission'], both.inputs[1])
        front = both.outputs['Shader']
        seen = nodes.new('ShaderNodeMath')
        seen.operation = 'SUBTRACT'
        seen.inputs[0].default_value = 1.0
        if not double_sided:
            links.new(geometry.outputs['Backfacing'], seen.inputs[1])
        aov = nodes.new('ShaderNodeOutputAOV')
        aov.name = LIGHT_AOV
        links.new(seen.outputs['Value'], aov.inputs['Value'])

    if double_sided:
        links.new(front, out.inputs['Surface'])
        mat.cycles.sample_as_light = True
        return mat

    # The back absorbs everything and emits nothing: a black diffuse BSDF ends the path.
    back = nodes.new('ShaderNodeBsdfDiffuse')
    back.inputs['Color'].default_value = (0.0, 0.0, 0.0, 1.0)
    mix = nodes.new('ShaderNodeMixShader')
    links.new(geometry.outputs['Backfacing'], mix.inputs['Fac'])  # Fac 1 picks the second shader
    links.new(front, mix.inputs[1])
    links.new(back.outputs['BSDF'], mix.inputs[2])
    links.new(mix.outputs['Shader'], out.inputs['Surface'])
    mat.cycles.sample_as_light = True  # emitters are sampled directly (next-event estimation)
    return mat


def replace_materials(gl):
    """Every glTF material becomes our Lambertian + emitter; the importer names Blender
    materials after the glTF ones, so map by name and insist that all are found."""
    ours = {}
    for i, m in enumerate(gl.get('materials', [])):
        pbr = m.get('pbrMetallicRoughness', {})
        rho = pbr.get('baseColorFactor', [1.0, 1.0, 1.0, 1.0])[:3]
        if 'baseColorTexture' in pbr:
            raise SystemExit('material %r has a base colour texture; this script handles factors only' % m.get('name'))
        strength = m.get('extensions', {}).get('KHR_materials_emissive_strength', {}).get('emissiveStrength', 1.0)
        emission = [c * strength for c in m.get('emissiveFactor', [0.0, 0.0, 0.0])]
        name = m.get('name') or 'material-%d' % i
        ours[name] = lambertian_material('ref-' + name, rho, emission, m.get('doubleSided', False))
    default = lambertian_material('ref-default', [1.0, 1.0, 1.0], [0.0, 0.0, 0.0])  # glTF's default material

    for obj in bpy.data.objects:
        if obj.type != 'MESH':
            continue
        if not obj.material_slots:
            obj.data.materials.append(default)
        for slot in obj.material_slots:
            imported = slot.material
            if imported is None:
                slot.material = default
                continue
            if imported == default or imported in ours.values():
                continue  # a mesh two nodes share: replaced through the first
            if imported.name not in ours:
                raise SystemExit('object %r: material %r is not in the glTF file' % (obj.name, imported.name))
            slot.link = 'DATA'
            slot.material = ours[imported.name]


def set_lights(scene, gl):
    """KHR_lights_punctual as the engine reads them: intensity (colour times `intensity`) is
    radiant intensity I in the scene's units, a point source (radius 0). A Cycles point or spot
    light of power P sends P / (4 pi) per steradian and a diffuse surface shows radiance rho E
    / pi, while here a pixel reads B = rho E (see the README: radiances are pi times physical
    ones), so P = 4 pi^2 I. A spot follows glTF's cone falloff (gltf_spot_falloff). Directional
    lights, which the engine ignores, are removed."""
    lights = gl.get('extensions', {}).get('KHR_lights_punctual', {}).get('lights', [])
    by_node = {}
    for node in gl.get('nodes', []):
        index = node.get('extensions', {}).get('KHR_lights_punctual', {}).get('light')
        if index is not None:
            by_node[node.get('name')] = lights[index]
    for obj in list(scene.objects):
        if obj.type != 'LIGHT':
            continue
        light = by_node.get(obj.name)
        if light is None:
            raise SystemExit('light object %r matches no glTF node with a punctual light' % obj.name)
        if light.get('type') == 'directional':
            bpy.data.objects.remove(obj, do_unlink=True)
            continue
        obj.data.color = light.get('color', [1.0, 1.0, 1.0])[:3]
        obj.data.energy = 4.0 * math.pi ** 2 * light.get('intensity', 1.0)
        obj.data.shadow_soft_size = 0.0
        if light.get('type') == 'spot':
            spot = light.get('spot', {})
            gltf_spot_falloff(obj.data, spot.get('innerConeAngle', 0.0), spot.get('outerConeAngle', math.pi / 4.0))


def gltf_spot_falloff(data, inner, outer):
    """A spot as glTF defines it: a point light whose intensity is scaled by s^2, s = clamp((cos a
    - cos outer) / (cos inner - cos outer), 0, 1), a the angle from the light's -Z axis. Blender's
    own spot (a smoothstep blend, times cos a in Cycles 3.x) sends up to 1.5 times the power of
    glTF's cone. Here the light is a Cycles point light whose emission strength is that factor,
    computed by shader nodes from the direction of emission (the light's Normal, in its own space)."""
    data.type = 'POINT'
    data.shadow_soft_size = 0.0
    data.use_nodes = True
    nodes, links = data.node_tree.nodes, data.node_tree.links
    emission = next(n for n in nodes if n.type == 'EMISSION')
    coords = nodes.new('ShaderNodeTexCoord')
    split = nodes.new('ShaderNodeSeparateXYZ')
    links.new(coords.outputs['Normal'], split.inputs['Vector'])
    # (cos a - cos outer) / (cos inner - cos outer) with cos a = -z: one multiply-add.
    span = max(math.cos(inner) - math.cos(outer), 1e-4)
    s = nodes.new('ShaderNodeMath')
    s.operation = 'MULTIPLY_ADD'
    s.use_clamp = True
    links.new(split.outputs['Z'], s.inputs[0])
    s.inputs[1].default_value = -1.0 / span
    s.inputs[2].default_value = -math.cos(outer) / span
    square = nodes.new('ShaderNodeMath')
    square.operation = 'MULTIPLY'
    links.new(s.outputs[0], square.inputs[0])
    links.new(s.outputs[0], square.inputs[1])
    links.new(square.outputs[0], emission.inputs['Strength'])


def set_camera(scene, gl, width, height):
    cams = [o for o in scene.objects if o.type == 'CAMERA']
    if len(cams) != 1:
        raise SystemExit('expected exactly one camera in the scene, found %d' % len(cams))
    cam = cams[0]
    gltf_cams = gl.get('cameras', [])
    if len(gltf_cams) != 1 or gltf_cams[0].get('type') != 'perspective':
        raise SystemExit('expected exactly one perspective glTF camera')
    persp = gltf_cams[0]['perspective']
    # The vertical field of view is yfov and the image aspect decides the horizontal one,
    # as in the engine (app/render/CameraView.cpp: perspective(yfov, width / height)).
    cam.data.type = 'PERSP'
    cam.data.sensor_fit = 'VERTICAL'
    cam.data.lens_unit = 'FOV'
    cam.data.angle_y = persp['yfov']
    cam.data.shift_x = cam.data.shift_y = 0.0
    cam.data.clip_start = persp.get('znear', 0.01)
    cam.data.clip_end = persp.get('zfar', 1e6)
    scene.camera = cam
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    return cam


def configure_cycles(scene, samples, seed):
    scene.render.engine = 'CYCLES'
    c = scene.cycles
    c.device = 'CPU'
    c.samples = samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = seed
    c.use_animated_seed = False
    c.max_bounces = 128
    c.diffuse_bounces = 128
    c.glossy_bounces = 0
    c.transmission_bounces = 0
    c.volume_bounces = 0
    c.transparent_max_bounces = 0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0  # the default (10) would cut bright indirect paths
    c.light_sampling_threshold = 0.0  # no probabilistic termination of light samples
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.blur_glossy = 0.0
    # The rasteriser samples one point at each pixel centre. Cycles ignores the width of its
    # Box filter (always 1 px, an area average), so use a Gaussian of Cycles' smallest width,
    # 0.01: its table spans 3 x width, so every sample lands within 0.015 px of the centre.
    c.pixel_filter_type = 'GAUSSIAN'
    c.filter_width = 0.01
    scene.render.film_transparent = False
    scene.render.use_compositing = True
    scene.render.dither_intensity = 0.0

    world = scene.world or bpy.data.worlds.new('World')
    scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes.get('Background')
    if bg is not None:
        bg.inputs['Color'].default_value = (0.0, 0.0, 0.0, 1.0)
        bg.inputs['Strength'].default_value = 0.0
    world.color = (0.0, 0.0, 0.0)

    vs = scene.view_settings
    vs.view_transform = 'Standard'
    vs.look = 'None'
    vs.exposure = 0.0
    vs.gamma = 1.0
    scene.sequencer_colorspace_settings.name = 'Linear'


def add_outputs(scene, folder):
    """Compositor: write Combined and the light AOV as 32-bit float EXR (linear)."""
    aov = scene.view_layers[0].aovs.add()
    aov.name = LIGHT_AOV
    aov.type = 'VALUE'
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    layers = tree.nodes.new('CompositorNodeRLayers')
    composite = tree.nodes.new('CompositorNodeComposite')
    tree.links.new(layers.outputs['Image'], composite.inputs['Image'])
    out = tree.nodes.new('CompositorNodeOutputFile')
    out.base_path = folder
    out.format.file_format = 'OPEN_EXR'
    out.format.color_depth = '32'
    out.format.exr_codec = 'ZIP'
    out.format.color_mode = 'RGB'
    out.file_slots.clear()
    out.file_slots.new('combined')
    out.file_slots.new('light')
    tree.links.new(layers.outputs['Image'], out.inputs['combined'])
    tree.links.new(layers.outputs[LIGHT_AOV], out.inputs['light'])


def load_rgb(path, width, height):
    """RGB floats of an EXR, rows bottom to top (Blender's order, and PFM's)."""
    img = bpy.data.images.load(path)
    if tuple(img.size) != (width, height):
        raise SystemExit('%s: size %r, expected %dx%d' % (path, tuple(img.size), width, height))
    rgba = array.array('f', [0.0]) * (width * height * 4)
    img.pixels.foreach_get(rgba)
    bpy.data.images.remove(img)
    rgb = array.array('f', [0.0]) * (width * height * 3)
    for i in range(width * height):
        rgb[3 * i:3 * i + 3] = rgba[4 * i:4 * i + 3]
    return rgb


def write_pfm(path, width, height, rgb):
    """Little-endian PFM (negative scale); rgb rows already bottom to top as PFM wants."""
    if sys.byteorder != 'little':
        rgb = array.array('f', rgb)
        rgb.byteswap()
    tmp = path + '.tmp'
    with open(tmp, 'wb') as f:
        f.write(b'PF\n%d %d\n-1.0\n' % (width, height))
        f.write(rgb.tobytes())
    os.replace(tmp, path)


def main():
    args = parse_args()
    gl, raw = read_gltf_json(args.scene)
    clear_scene()
    bpy.ops.import_scene.gltf(filepath=os.path.abspath(args.scene), import_shading='FLAT', merge_vertices=False)
    scene = bpy.context.scene
    replace_materials(gl)
    set_lights(scene, gl)
    set_camera(scene, gl, args.width, args.height)
    configure_cycles(scene, args.samples, args.seed)

    with tempfile.TemporaryDirectory(prefix='cycles-reference-') as folder:
        add_outputs(scene, folder)
        scene.frame_set(1)
        start = time.monotonic()
        bpy.ops.render.render(write_still=False)
        seconds = time.monotonic() - start
        combined = load_rgb(os.path.join(folder, 'combined0001.exr'), args.width, args.height)
        seen = load_rgb(os.path.join(folder, 'light0001.exr'), args.width, args.height)

    # All samples of a pixel fall within 0.015 px of its centre (filter above), so a pixel
    # whose samples mostly see a light is one whose centre does: what the rasteriser draws.
    lights = array.array('f', [1.0 if v >= 0.5 else 0.0 for v in seen])
    if not all(math.isfinite(v) for v in combined):
        raise SystemExit('the render has non-finite pixels')

    prefix = args.out_prefix
    os.makedirs(os.path.dirname(os.path.abspath(prefix)), exist_ok=True)
    write_pfm(prefix + '.pfm', args.width, args.height, combined)
    write_pfm(prefix + '-lights.pfm', args.width, args.height, lights)
    c = scene.cycles
    meta = {
        'command': 'blender -b --factory-startup --python bench/cycles/render_reference.py -- ' +
                   ' '.join(sys.argv[sys.argv.index('--') + 1:]),
        'blender': bpy.app.version_string,
        'scene': os.path.basename(args.scene),
        'scene_sha256': hashlib.sha256(raw).hexdigest(),
        'scene_fnv1a64': fnv1a64(raw),
        'size': [args.width, args.height],
        'samples': args.samples,
        'seed': args.seed,
        'render_seconds': round(seconds, 1),
        'threads': scene.render.threads,
        'settings': {'max_bounces': c.max_bounces, 'diffuse_bounces': c.diffuse_bounces,
                     'pixel_filter': c.pixel_filter_type, 'filter_width_px': round(c.filter_width, 4),
                     'clamp_direct': c.sample_clamp_direct, 'clamp_indirect': c.sample_clamp_indirect,
                     'adaptive_sampling': c.use_adaptive_sampling, 'denoising': c.use_denoising,
                     'view_transform': scene.view_settings.view_transform},
        'light_pixels': int(sum(1 for i in range(0, len(lights), 3) if lights[i] > 0.0)),
    }
    with open(prefix + '.json', 'w') as f:
        json.dump(meta, f, indent=1)
        f.write('\n')
    print('wrote %s.pfm, %s-lights.pfm, %s.json (%.1f s)' % (prefix, prefix, prefix, seconds))


if __name__ == '__main__':
    main()
