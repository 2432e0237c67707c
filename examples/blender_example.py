"""The Blender part of the main job (scripts/example.sh), run headless:

    blender -b --factory-startup --python-exit-code 1 -P examples/blender_example.py -- OUTDIR

Part 1, genus 0 through the sphere: loads Spot and the penguin, places the features of a features file
(name -> [vertex per mesh]) as CM: vertex groups, computes their consistent parameterization, morphs
the first into the second (shape key, animated 0 -> 1 -> 0 over frames 1-24), gives the first a UV map
(Smart UV Project) and a generated colour-grid texture and bakes that texture and the first's normals (a
tangent-space normal map) into the second's own UV layout. Writes OUTDIR/example.blend,
OUTDIR/morph_contact_sheet.png (the 24 frames, left to right, top to bottom), OUTDIR/texture_transfer.png
(source and target side by side) and OUTDIR/normal_transfer.png (Cycles, grey: the source, the target
with its own normals, the target with the source's baked normals).

Part 2, genus 1 without the sphere: the kitten and the torus, no features, mapped directly onto each
other (the inter-surface map through a consistent partition); a colour attribute painted on the kitten
is carried onto the torus and the kitten morphs into the torus. Writes OUTDIR/kitten_torus.blend,
OUTDIR/pair_morph_contact_sheet.png, OUTDIR/colour_transfer.png and OUTDIR/pair_distortion.png (each face of
both coloured by how the map onto the other stretches it).

Uses consistent_maps.api from addon/ (the native module is built there by scripts/setup.sh); nothing is
installed.
"""
import json
import math
import sys
import time
from pathlib import Path

import bpy
import numpy as np
from mathutils import Matrix

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "addon"))
from consistent_maps import _native, api  # noqa: E402

MESHES = ROOT / "examples" / "meshes"
SOURCE, TARGET = "spot", "penguin"
PAIR_SOURCE, PAIR_TARGET = "kitten", "torus"  # genus 1: kitten.off, torus.obj
FEATURES = ROOT / "examples" / "spot_penguin_features.json"  # name -> [vertex on SOURCE, vertex on TARGET]
FRAMES, COLUMNS, CELL = 24, 6, 160
PAIR_REMESH = 24  # the pair's remeshes: 24^2 + 2 vertices
TEXTURE_SIZE, BAKE_SIZE = 1024, 1024

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(args) != 1:
    sys.exit("usage: blender -b --factory-startup --python-exit-code 1 -P examples/blender_example.py -- OUTDIR")
OUT = Path(args[0]).resolve()
OUT.mkdir(parents=True, exist_ok=True)
START = time.perf_counter()


def step(text, since):
    print(f"[blender example] {text} ({time.perf_counter() - since:.2f} s)", flush=True)
    return time.perf_counter()


def load(file_name, turn):
    """The mesh file as a new object named after it, stood up (the files are y-up, Blender is z-up) and
    turned by `turn` about z."""
    name = Path(file_name).stem
    vertices, triangles = _native.read_mesh(str(MESHES / file_name))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices.tolist(), [], triangles.tolist())
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    obj.rotation_euler = (math.pi / 2, 0, turn)
    for polygon in mesh.polygons:
        polygon.use_smooth = True
    return obj


def select_only(obj):
    for other in bpy.context.view_layer.objects:
        other.select_set(other == obj)
    bpy.context.view_layer.objects.active = obj


def smart_uv(obj):
    select_only(obj)
    obj.data.uv_layers.new(name="UVMap")
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.uv.smart_project(island_margin=0.02)
    bpy.ops.object.mode_set(mode='OBJECT')


def textured_material(name, image, uv_map="UVMap"):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = uv_map
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    links.new(uv.outputs["UV"], texture.inputs["Vector"])
    links.new(texture.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
    nodes.active = texture  # what Workbench's Texture colour shows
    return material


def grey_material(name):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    principled = material.node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (0.7, 0.7, 0.7, 1)
    principled.inputs["Roughness"].default_value = 0.6
    return material


def add_normal_map(material, image, uv_map="UVMap"):
    """Feeds the tangent-space normal map image (at uv_map) into the material's Principled BSDF."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = uv_map
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    normal_map = nodes.new("ShaderNodeNormalMap")
    normal_map.uv_map = uv_map
    links.new(uv.outputs["UV"], texture.inputs["Vector"])
    links.new(texture.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs["Normal"], nodes["Principled BSDF"].inputs["Normal"])


def world_bounds(objects):
    corners = np.array([obj.matrix_world @ v.co for obj in objects for v in obj.data.vertices])
    return corners.min(axis=0), corners.max(axis=0)


def camera_on(objects, aspect):
    """An orthographic camera looking along +y at the objects (world bounds), framing them with a margin."""
    scene = bpy.context.scene
    camera = scene.camera or bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    if camera.name not in scene.collection.objects:
        scene.collection.objects.link(camera)
    low, high = world_bounds(objects)
    centre, size = (low + high) / 2, high - low
    camera.data.type = 'ORTHO'
    camera.data.ortho_scale = 1.1 * max(size[0], size[2] * aspect)
    camera.location = (centre[0], low[1] - 10, centre[2])
    camera.rotation_euler = (math.pi / 2, 0, 0)
    camera.data.clip_end = 100
    scene.camera = camera


def use_workbench(color_type):
    """Renders the scene with Workbench (studio light, grey background), colouring by color_type."""
    scene = bpy.context.scene
    scene.render.engine = 'BLENDER_WORKBENCH'
    scene.display.shading.light = 'STUDIO'
    scene.display.shading.color_type = color_type
    scene.render.image_settings.file_format = 'PNG'
    scene.render.film_transparent = False
    scene.view_settings.view_transform = 'Standard'
    scene.world = scene.world or bpy.data.worlds.new("World")
    scene.world.color = (0.6, 0.6, 0.6)


def render(width, height):
    """Renders the scene (Workbench) and returns its pixels, (height, width, 4), rows top to bottom."""
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    path = OUT / "_frame.png"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(path))
    pixels = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    path.unlink()
    return pixels.reshape(height, width, 4)[::-1]


def save_png(pixels, path):
    height, width = pixels.shape[:2]
    image = bpy.data.images.new(path.stem, width, height, alpha=True)
    image.pixels.foreach_set(pixels[::-1].ravel())
    image.filepath_raw = str(path)
    image.file_format = 'PNG'
    image.save()
    bpy.data.images.remove(image)


def render_morph(obj, path):
    """Renders frames 1-FRAMES of obj's morph (what else renders stays in) into one contact sheet at path,
    the camera framing both ends of the morph."""
    scene = bpy.context.scene
    morphed = []
    for frame in (1, 1 + FRAMES // 2):
        scene.frame_set(frame)
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
        mesh = evaluated.to_mesh()
        morphed += [evaluated.matrix_world @ v.co for v in mesh.vertices]
        evaluated.to_mesh_clear()
    corners = np.array(morphed)
    frame_box = bpy.data.objects.new("_bounds", bpy.data.meshes.new("_bounds"))
    frame_box.data.from_pydata([tuple(corners.min(axis=0)), tuple(corners.max(axis=0))], [], [])
    scene.collection.objects.link(frame_box)
    camera_on([frame_box], 1.0)
    bpy.data.objects.remove(frame_box)
    sheet = np.ones((math.ceil(FRAMES / COLUMNS) * CELL, COLUMNS * CELL, 4), dtype=np.float32)
    for frame in range(1, FRAMES + 1):
        scene.frame_set(frame)
        row, column = divmod(frame - 1, COLUMNS)
        sheet[row * CELL:(row + 1) * CELL, column * CELL:(column + 1) * CELL] = render(CELL, CELL)
    save_png(sheet, path)


# -- 1. load the meshes and place the features ---------------------------------------------------------------
t = START
bpy.ops.wm.read_homefile(use_empty=True)
# Spot faces -z and the penguin +z in their files: both turned to a three-quarter view of the camera at -y.
source, target = load(f"{SOURCE}.obj", math.pi * 0.8), load(f"{TARGET}.obj", -math.pi * 0.2)
features = json.loads(FEATURES.read_text())
for name, (on_source, on_target) in features.items():
    api.add_feature(source, name, on_source)
    api.add_feature(target, name, on_target)
t = step(f"loaded {SOURCE} ({len(source.data.vertices)} vertices) and {TARGET} ({len(target.data.vertices)}), "
         f"{len(features)} features from {FEATURES.name} as CM: vertex groups", t)

# -- 2. the consistent parameterization ----------------------------------------------------------------------
stats = api.compute([source, target], effort=1)
efficiencies = ", ".join(f"{name} {values['efficiency']:.3f}" for name, values in stats.items())
t = step(f"consistent set computed; stretch efficiency {efficiencies}", t)

# -- 3. the morph, animated ----------------------------------------------------------------------------------
key = api.morph(source, target, align='features')
api.animate_morph(source, 1, FRAMES, ping_pong=True)
scene = bpy.context.scene
scene.frame_start, scene.frame_end = 1, FRAMES
t = step(f"shape key '{key.name}' on {SOURCE}, keyframed 0 -> 1 -> 0 over frames 1-{FRAMES}", t)

# -- 4. a texture on the source, baked into the target's UV layout -------------------------------------------
smart_uv(source)
smart_uv(target)
grid = bpy.data.images.new("Colour grid", TEXTURE_SIZE, TEXTURE_SIZE)
grid.generated_type = 'COLOR_GRID'
source.data.materials.append(textured_material(f"{SOURCE} grid", grid))
baked = api.bake_texture(source, target, BAKE_SIZE)
baked.pack()
target_material = textured_material(f"{TARGET} from {SOURCE}", baked)
target.data.materials.append(target_material)
t = step(f"UV maps by Smart UV Project, {TEXTURE_SIZE}² colour grid on {SOURCE}, baked into {TARGET}'s UV "
         f"layout ({BAKE_SIZE}² image '{baked.name}', packed)", t)

# -- 4b. the source's normals, baked into the target's UV layout as a tangent-space normal map ---------------
normals = api.bake_normal_map(source, target, BAKE_SIZE, align='features')
normals.pack()
add_normal_map(target_material, normals)
t = step(f"{SOURCE}'s normals baked into {TARGET}'s UV layout ({BAKE_SIZE}² normal map '{normals.name}', "
         f"packed, in its material: {TARGET} wears {SOURCE}'s texture and surface detail)", t)

# -- 5. the .blend -------------------------------------------------------------------------------------------
use_workbench('TEXTURE')
target.location.x = 1.3 * (world_bounds([source])[1][0] - world_bounds([target])[0][0])
scene.frame_set(1)
camera_on([source, target], 2 / 1)  # the file opens with the side-by-side view (F12 renders it)
scene.render.resolution_x, scene.render.resolution_y = 640, 320
blend = OUT / "example.blend"
bpy.ops.wm.save_as_mainfile(filepath=str(blend))
t = step(f"saved {blend}", t)

# -- 6. renders ----------------------------------------------------------------------------------------------
target.hide_render = True
render_morph(source, OUT / "morph_contact_sheet.png")
t = step(f"rendered {FRAMES} frames (Workbench, {CELL}x{CELL}) to {OUT / 'morph_contact_sheet.png'}", t)

scene.frame_set(1)
target.hide_render = False
camera_on([source, target], 2 / 1)
save_png(render(640, 320), OUT / "texture_transfer.png")
t = step(f"rendered {SOURCE} (its texture) and {TARGET} (the baked transfer) to {OUT / 'texture_transfer.png'}", t)

# Normals need a renderer that shades with them: Cycles, grey materials, a sun grazing the front. The target
# moves one place right; a copy with the target's own normals takes its place.
plain = bpy.data.objects.new(f"{TARGET} (own normals)", target.data.copy())
scene.collection.objects.link(plain)
plain.matrix_world = target.matrix_world.copy()
target.location.x *= 2  # the source stands at the origin
bpy.context.view_layer.update()  # matrix_world, which camera_on reads, follows the new location
grey, grey_with_normals = grey_material("grey"), grey_material(f"grey, {SOURCE}'s normals")
add_normal_map(grey_with_normals, normals)
for obj, material in ((source, grey), (plain, grey), (target, grey_with_normals)):
    obj.data.materials.clear()
    obj.data.materials.append(material)
sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
sun.data.energy = 2
scene.world.color = (0.15, 0.15, 0.15)  # dim ambient light: the sun's shading shows the normals
sun.rotation_euler = (math.radians(60), 0, math.radians(-20))
scene.collection.objects.link(sun)
scene.render.engine = 'CYCLES'
scene.cycles.samples, scene.cycles.use_denoising = 16, False
camera_on([source, plain, target], 3 / 1)
save_png(render(960, 320), OUT / "normal_transfer.png")
t = step(f"rendered {SOURCE}, {TARGET} with its own normals and {TARGET} with {SOURCE}'s baked normals (Cycles) "
         f"to {OUT / 'normal_transfer.png'}", t)

# -- 7. genus 1: two objects with a handle, mapped onto each other without the sphere ------------------------
bpy.ops.wm.read_homefile(use_empty=True)
scene = bpy.context.scene
pair_source, pair_target = load(f"{PAIR_SOURCE}.off", math.pi * 0.15), load(f"{PAIR_TARGET}.obj", math.pi * 0.1)
# The torus lies flat in its file (its ring in the xz plane, y up): stood up in its own coordinates, facing +z like
# the kitten, so that the kitten's morph (made in the kitten's coordinates) stands up too.
pair_target.data.transform(Matrix.Rotation(math.pi / 2, 4, 'X'))
# A colour per vertex of the kitten: its position as a colour, in bands across its height.
points = np.array([v.co[:] for v in pair_source.data.vertices])
low, high = points.min(axis=0), points.max(axis=0)
colours = np.ones((len(points), 4))
colours[:, :3] = 0.25 + 0.75 * (points - low) / (high - low)
colours[:, :3] *= 0.7 + 0.3 * (np.floor(8 * (points[:, 1] - low[1]) / (high[1] - low[1])) % 2)[:, None]
layer = pair_source.data.color_attributes.new("Colour", 'FLOAT_COLOR', 'POINT')
layer.data.foreach_set("color", colours.astype(np.float32).ravel())
pair_source.data.color_attributes.active_color = layer
t = step(f"loaded {PAIR_SOURCE} ({len(pair_source.data.vertices)} vertices, genus 1) and {PAIR_TARGET} "
         f"({len(pair_target.data.vertices)}, genus 1), no features; colour attribute 'Colour' on {PAIR_SOURCE}", t)

stats = api.compute([pair_source, pair_target], effort=1)
medians = " / ".join(f"{values['median_symmetric_dirichlet']:.2f}" for values in stats.values())
t = step(f"inter-surface map computed ({stats[PAIR_SOURCE]['method']}, no sphere): median symmetric Dirichlet "
         f"{medians} (both directions, optimum 4), bijective {stats[PAIR_SOURCE]['bijective']}", t)

api.transfer(pair_source, pair_target, color_attributes=["Colour"])
pair_target.data.color_attributes.active_color = pair_target.data.color_attributes["Colour"]
key = api.morph(pair_source, pair_target, align='bounds')
api.animate_morph(pair_source, 1, FRAMES, ping_pong=True)
scene.frame_start, scene.frame_end = 1, FRAMES
t = step(f"'Colour' carried onto {PAIR_TARGET}; shape key '{key.name}' on {PAIR_SOURCE}, keyframed 0 -> 1 -> 0", t)

use_workbench('VERTEX')
pair_target.location.x = 1.3 * (world_bounds([pair_source])[1][0] - world_bounds([pair_target])[0][0])
scene.frame_set(1)
camera_on([pair_source, pair_target], 2 / 1)
scene.render.resolution_x, scene.render.resolution_y = 640, 320
blend = OUT / "kitten_torus.blend"
bpy.ops.wm.save_as_mainfile(filepath=str(blend))
save_png(render(640, 320), OUT / "colour_transfer.png")
pair_target.hide_render = True
render_morph(pair_source, OUT / "pair_morph_contact_sheet.png")
t = step(f"saved {blend}; rendered {OUT / 'colour_transfer.png'} ({PAIR_SOURCE} and {PAIR_TARGET} with the "
         f"carried colours) and {OUT / 'pair_morph_contact_sheet.png'}", t)

# Where the map stretches: each face coloured by its distortion onto the other (white as is, red stretched).
scene.frame_set(1)
pair_target.hide_render = False
camera_on([pair_source, pair_target], 2 / 1)
shown = [api.show_distortion(obj, other) for obj, other in ((pair_source, pair_target), (pair_target, pair_source))]
save_png(render(640, 320), OUT / "pair_distortion.png")
t = step(f"rendered {OUT / 'pair_distortion.png'}: each face by its symmetric Dirichlet energy onto the other "
         f"(white 4, yellow 16, red 64 and more); median " + " / ".join(f"{s['median']:.2f}" for s in shown) +
         ", share of the area at 16 or more " + " / ".join(f"{s['high_area']:.1%}" for s in shown), t)

# Consistent remeshes of the pair, through its map: one connectivity on both, drawn as wireframes.
scene.frame_set(1)
remeshes = api.remesh([pair_source, pair_target], PAIR_REMESH)
for obj in (pair_source, pair_target):
    obj.hide_render = True
for obj in remeshes:
    co = np.array([v.co[:] for v in obj.data.vertices])
    edges = np.array([e.vertices[:] for e in obj.data.edges])
    obj.modifiers.new("Wireframe", 'WIREFRAME').thickness = 0.05 * np.linalg.norm(co[edges[:, 0]] - co[edges[:, 1]],
                                                                                   axis=1).mean()
use_workbench('SINGLE')
camera_on(remeshes, 2 / 1)
save_png(render(640, 320), OUT / "pair_remeshes.png")
t = step(f"consistent remeshes of {PAIR_SOURCE} and {PAIR_TARGET}, {len(remeshes[0].data.vertices)} vertices each, one "
         f"connectivity ({len(remeshes[0].data.polygons)} triangles); rendered {OUT / 'pair_remeshes.png'}", t)
step("done", START)
