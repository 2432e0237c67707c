"""Texture and normal-map transfer: the source's image texture or surface normals baked into the target's
own UV layout through the map.

Texture: the target's corners get, through the map, the source UV they land on (seam-aware,
as in transfer); a temporary copy of the target, whose material shows the source image at
those UVs as emission, is baked by Cycles into a new image in the target's UV layout
(Blender rasterizes and pads the seams).

Normal map: Cycles bakes, for a temporary copy of the target, what it interpolates per pixel
of the target's UV layout: where the pixel lands on the source and Blender's tangent frame
of that UV map (MikkTSpace tangent, bitangent sign and normal per corner, from
mesh.calc_tangents, stored on the copy as corner attributes). Through the sphere a pixel's
sphere direction (the stored map) is located on the source (native point location); a pair
mapped directly stores no sphere, so the pixel's point of the chord triangle between its
triangle's corners' images on the source is taken to the nearest point of the source (exact
at the corners, as near to the map inside each triangle as the texture bake's interpolated
UVs). That gives the source's normal there (its shading normal, with its own tangent-space
normal map applied when its material has one; turned by the features' rotation with
align='features'), and the pixel becomes that normal expressed in the pixel's frame: the
exact inverse of what Blender's Normal Map node decodes, so the target rendered with the map
shows the source's normals. The target itself is not modified.
"""
import contextlib
import os

import bpy
import numpy as np

from . import alignment, mapping, maps, meshdata, morphs, native, results

SOURCE_UV = "cm_bake_source_uv"
SPHERE_ATTRIBUTE = results.ATTRIBUTE  # the stored sphere coordinates, a point attribute
IMAGE_ATTRIBUTE = "cm_bake_image"  # a pair's vertices' images on the source, in the source's box scaled to [-1, 1]
FRAME_TANGENT, FRAME_NORMAL, FRAME_SIGN = "cm_bake_tangent", "cm_bake_normal", "cm_bake_sign"
NORMAL_ALIGN = ('none', 'features')


def source_image(obj):
    """(image, UV map name) of the first image texture in obj's materials, or None."""
    for slot in obj.material_slots:
        material = slot.material
        if material is None or not material.use_nodes:
            continue
        for node in material.node_tree.nodes:
            if node.type == 'TEX_IMAGE' and node.image is not None:
                uv = node.inputs["Vector"].links[0].from_node if node.inputs["Vector"].is_linked else None
                name = uv.uv_map if uv is not None and uv.type == 'UVMAP' and uv.uv_map else None
                active = obj.data.uv_layers.active
                return node.image, name or (active.name if active else None)
    return None


def _target_problems(target, size):
    found = []
    if not target.data.uv_layers:
        found.append(f"'{target.name}' has no UV map to bake into: unwrap it first (UV > Unwrap)")
    if not hasattr(bpy.context.scene, "cycles"):
        found.append("Baking needs the Cycles render engine: enable the Cycles add-on")
    if not 16 <= size <= 16384:
        found.append(f"The image size must be between 16 and 16384 pixels, not {size}")
    return found


def _problems(source, target, size):
    found = maps.problems([source, target])
    if found:
        return found
    texture = source_image(source)
    if texture is None:
        found.append(f"'{source.name}' has no image texture in its materials: nothing to bake")
    elif texture[1] is None:
        found.append(f"'{source.name}' has no UV map for its image texture")
    return found + _target_problems(target, size)


class _Steps:
    """Reports each of `count` equal steps as it finishes to progress(fraction) (None: nobody listens)."""

    def __init__(self, progress, count):
        self.progress, self.count, self.finished = progress, count, 0

    def done(self):
        self.finished += 1
        if self.progress is not None:
            self.progress(self.finished / self.count)


def _material(build):
    """A new node material whose tree build(nodes, links) fills (after clearing)."""
    material = bpy.data.materials.new("CM bake")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    links.new(build(nodes, links), output.inputs["Surface"])
    return material


def _emission(nodes, links, color_socket):
    emission = nodes.new("ShaderNodeEmission")
    links.new(color_socket, emission.inputs["Color"])
    return emission.outputs["Emission"]


@contextlib.contextmanager
def _baking_copy(target, mesh=None):
    """A temporary object with a copy of target's mesh (or the given temporary mesh; same transform),
    selected and active alone, with Cycles at 1 sample; everything (objects, selection, engine, materials
    made meanwhile, the mesh) is restored or removed after."""
    scene, layer = bpy.context.scene, bpy.context.view_layer
    mesh = target.data.copy() if mesh is None else mesh
    copy = bpy.data.objects.new("CM bake", mesh)
    copy.matrix_world = target.matrix_world.copy()
    scene.collection.objects.link(copy)
    selected, active = list(bpy.context.selected_objects), layer.objects.active
    engine, samples, denoise = scene.render.engine, scene.cycles.samples, scene.cycles.use_denoising
    materials = set(bpy.data.materials)
    try:
        for obj in selected:
            obj.select_set(False)
        copy.select_set(True)
        layer.objects.active = copy
        scene.render.engine = 'CYCLES'
        scene.cycles.samples = 1
        scene.cycles.use_denoising = False  # nothing to denoise, and builds without OpenImageDenoise fail
        yield copy, mesh
    finally:
        scene.render.engine, scene.cycles.samples, scene.cycles.use_denoising = engine, samples, denoise
        bpy.data.objects.remove(copy)
        bpy.data.meshes.remove(mesh)
        for material in set(bpy.data.materials) - materials:
            bpy.data.materials.remove(material)
        for obj in selected:
            obj.select_set(True)
        layer.objects.active = active


def _bake_into(mesh, material, image, bake_type, margin, **options):
    """Bakes the (selected, active) copy with the one material into image."""
    mesh.materials.clear()
    mesh.materials.append(material)
    mesh.polygons.foreach_set("material_index", np.zeros(len(mesh.polygons), dtype=np.int32))
    mesh.update()
    nodes = material.node_tree.nodes
    node = nodes.new("ShaderNodeTexImage")
    node.image = image
    nodes.active = node
    try:
        bpy.ops.object.bake(type=bake_type, margin=margin, use_clear=True, **options)
    except RuntimeError as e:
        raise maps.MapError(f"Baking failed: {e}") from e


def _float_image(name, size):
    image = bpy.data.images.new(name, size, size, alpha=True, float_buffer=True)
    image.colorspace_settings.name = 'Non-Color'
    return image


def _pixels(image):
    values = np.empty(image.size[0] * image.size[1] * 4, dtype=np.float32)
    image.pixels.foreach_get(values)
    return values.reshape(-1, 4)


def bake(source, target, size=1024, margin=16, progress=None):
    """A new image (size x size) of source's image texture in target's active UV layout; raises
    maps.MapError (nothing created or modified) when it cannot be baked. progress(fraction) is called as
    the steps finish."""
    found = _problems(source, target, size)
    if found:
        raise maps.MapError("\n".join(found))
    steps = _Steps(progress, 2)
    image, uv_map = source_image(source)
    layer_data = source.data.uv_layers[uv_map].data
    source_uv = np.empty(len(layer_data) * 2, dtype=np.float32)
    layer_data.foreach_get("uv", source_uv)
    uv = maps.uvs_at_corners(source, target, maps.corner_landing(source, target), source_uv.reshape(-1, 2))
    steps.done()
    result = bpy.data.images.new(f"{target.name} from {source.name}", size, size, alpha=False)

    def emit_source_image(nodes, links):
        uv_node = nodes.new("ShaderNodeUVMap")
        uv_node.uv_map = SOURCE_UV
        texture = nodes.new("ShaderNodeTexImage")
        texture.image = image
        links.new(uv_node.outputs["UV"], texture.inputs["Vector"])
        return _emission(nodes, links, texture.outputs["Color"])
    try:
        with _baking_copy(target) as (_, mesh):
            mesh.uv_layers.new(name=SOURCE_UV).data.foreach_set("uv", uv.astype(np.float32).ravel())
            mesh.uv_layers.active = mesh.uv_layers[target.data.uv_layers.active.name]
            _bake_into(mesh, _material(emit_source_image), result, 'EMIT', margin)
    except maps.MapError:
        bpy.data.images.remove(result)
        raise
    steps.done()
    return result


def _normal_problems(source, target, size, align):
    found = maps.problems([source, target])
    if found:
        return found
    if align not in NORMAL_ALIGN:
        found.append(f"Unknown alignment '{align}': use one of {', '.join(NORMAL_ALIGN)}")
    elif align == 'features':
        try:
            morphs.shared_features(source, target)
        except maps.MapError as e:
            found.append(str(e).replace("choose another alignment", "bake with align 'none'"))
    for obj in [target] + ([source] if source_normal_map(source) is not None else []):
        if _has_ngons(obj.data):
            found.append(f"'{obj.name}' has faces with more than 4 corners, for which Blender computes no tangent "
                         f"space: triangulate them (Face > Triangulate Faces)")
    return found + _target_problems(target, size)


def _has_ngons(mesh):
    sizes = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_total", sizes)
    return bool((sizes > 4).any())


def _normal_rotation(source, target, align):
    """(3, 3) taking source object-space normals to target object space."""
    if align == 'none':
        return np.eye(3)
    source_vertices, target_vertices = morphs.shared_features(source, target)
    return alignment.rotation(maps.positions(source.data)[source_vertices],
                              maps.positions(target.data)[target_vertices])


def source_normal_map(obj):
    """(image, UV map name, strength) of the first tangent-space Normal Map node fed by an image texture in
    obj's materials, or None."""
    for slot in obj.material_slots:
        material = slot.material
        if material is None or not material.use_nodes:
            continue
        for node in material.node_tree.nodes:
            if node.type != 'NORMAL_MAP' or node.space != 'TANGENT' or not node.inputs["Color"].is_linked:
                continue
            texture = node.inputs["Color"].links[0].from_node
            if texture.type != 'TEX_IMAGE' or texture.image is None:
                continue
            strength = node.inputs["Strength"]
            active = obj.data.uv_layers.active
            uv_map = node.uv_map or (active.name if active else None)
            if uv_map is None or uv_map not in obj.data.uv_layers:
                continue
            return texture.image, uv_map, 1.0 if strength.is_linked else float(strength.default_value)
    return None


def _sample(image, uv):
    """Bilinear samples (q, 4) of the image at UVs (q, 2), repeating beyond [0, 1]."""
    width, height = image.size
    pixels = _pixels(image).reshape(height, width, 4).astype(np.float64)
    x, y = uv[:, 0] * width - 0.5, uv[:, 1] * height - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]
    x0, y0 = x0.astype(np.int64), y0.astype(np.int64)
    x1, y1 = (x0 + 1) % width, (y0 + 1) % height
    x0, y0 = x0 % width, y0 % height
    return ((1 - fy) * ((1 - fx) * pixels[y0, x0] + fx * pixels[y0, x1])
            + fy * ((1 - fx) * pixels[y1, x0] + fx * pixels[y1, x1]))


def _read_loops(mesh, field, width):
    values = np.empty(len(mesh.loops) * width, dtype=np.float32)
    mesh.loops.foreach_get(field, values)
    return values.reshape(-1, width).astype(np.float64) if width > 1 else values.astype(np.float64)


def _mapped_normals(source, landing, corners, shading, normal_map):
    """Source's normals at the landing points with its tangent-space normal map applied (as Blender's
    Normal Map node does: the map's colour in the MikkTSpace frame of its UV map, mixed by its strength)."""
    image, uv_map, strength = normal_map
    mesh = source.data
    uv = mapping.at_corners(landing, corners, _uv(mesh, uv_map))
    tangent_space = _sample(image, uv)[:, :3] * 2 - 1
    mesh.calc_tangents(uvmap=uv_map)
    try:
        tangents = mapping.at_corners(landing, corners, _read_loops(mesh, "tangent", 3))
        signs = np.where(mapping.at_corners(landing, corners, _read_loops(mesh, "bitangent_sign", 1)) < 0, -1.0, 1.0)
    finally:
        mesh.free_tangents()
    bitangents = signs[:, None] * np.cross(shading, tangents)
    mapped = (tangent_space[:, :1] * tangents + tangent_space[:, 1:2] * bitangents
              + tangent_space[:, 2:] * shading)
    mapped /= np.maximum(np.linalg.norm(mapped, axis=1, keepdims=True), 1e-12)
    return shading + strength * (mapped - shading)


def _uv(mesh, name):
    values = np.empty(len(mesh.loops) * 2, dtype=np.float32)
    mesh.uv_layers[name].data.foreach_get("uv", values)
    return values.reshape(-1, 2).astype(np.float64)


def _source_normals_at(source, landing, rotation):
    """Source's normals (unit, rotated) at the landing points: its shading normals, with its own tangent-space
    normal map applied when its material has one."""
    from .transfer import corner_normals
    corners = meshdata.loop_triangles(source.data)[1]
    normals = mapping.at_corners(landing, corners, corner_normals(source.data))
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    normal_map = source_normal_map(source)
    if normal_map is not None:
        normals = _mapped_normals(source, landing, corners, normals, normal_map)
    normals = normals @ rotation.T
    return normals / np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)


def _bake_attribute(mesh, name, size, margin):
    """(size², 3) the copy's float attribute `name` (values in [-1, 1]) interpolated at every pixel of its
    active UV layout, as Cycles interpolates it (margin pixels copied outwards)."""
    image = _float_image(f"CM bake {name}", size)

    def emit_attribute(nodes, links):
        attribute = nodes.new("ShaderNodeAttribute")
        attribute.attribute_name = name
        encode = nodes.new("ShaderNodeVectorMath")  # 0.5 v + 0.5: emission stays non-negative
        encode.operation = 'MULTIPLY_ADD'
        encode.inputs[1].default_value = (0.5, 0.5, 0.5)
        encode.inputs[2].default_value = (0.5, 0.5, 0.5)
        links.new(attribute.outputs["Vector"], encode.inputs[0])
        return _emission(nodes, links, encode.outputs["Vector"])
    try:
        _bake_into(mesh, _material(emit_attribute), image, 'EMIT', margin)
        return _pixels(image)[:, :3].astype(np.float64) * 2 - 1
    finally:
        bpy.data.images.remove(image)


def _image_attribute(mesh, source, target):
    """Stores on the copy of a pair's target each vertex's image on the source (source object space) as the
    point attribute IMAGE_ATTRIBUTE, boxed into [-1, 1] (baked emission stays non-negative); returns (centre,
    half size) to decode it."""
    triangles = meshdata.loop_triangles(source.data)[0]
    images = mapping.at_vertices(maps.vertex_landing(target, source), triangles, maps.positions(source.data))
    low, high = images.min(axis=0), images.max(axis=0)
    centre, half = (low + high) / 2, np.maximum((high - low) / 2, 1e-9) * 1.01
    mesh.attributes.new(IMAGE_ATTRIBUTE, 'FLOAT_VECTOR', 'POINT').data.foreach_set(
        "vector", ((images - centre) / half).astype(np.float32).ravel())
    return centre, half


def _nearest_on(source, points):
    """Landing of the points of source nearest to the given points (source object space)."""
    triangles = meshdata.loop_triangles(source.data)[0]
    located, barycentric, _ = native.surface_locator(maps.positions(source.data), triangles).locate(
        points, threads=os.cpu_count() or 1)
    return mapping.Landing(located.astype(np.int64), barycentric)


def _tangent_frames(mesh, uv_map):
    """Per corner (tangent (c, 3), bitangent sign (c,), normal (c, 3)) of Blender's tangent space of uv_map
    (MikkTSpace, object space), as the Normal Map node uses them."""
    mesh.calc_tangents(uvmap=uv_map)
    try:
        return _read_loops(mesh, "tangent", 3), _read_loops(mesh, "bitangent_sign", 1), _read_loops(mesh, "normal", 3)
    finally:
        mesh.free_tangents()


def _refined_copy(target, uv_map):
    """A temporary mesh of target's map: its refined triangles (Steiner vertices inside the input ones),
    on which the map is linear, with their sphere points and uv_map's layout (each refined corner's
    coordinates interpolated in its input triangle). The sphere point a pixel gets from it is the map's
    own; the input triangles would interpolate straight across the paths' bends."""
    p = maps.parameterization(target)
    vertices, triangles, sphere = results.surface(target.data)
    corners = meshdata.loop_triangles(target.data)[1][p.input_triangle]      # (M', 3) input corners (loops)
    uv = np.einsum("rjk,rkd->rjd", mapping.refined_in_input(p), _uv(target.data, uv_map)[corners])
    mesh = results.surface_mesh("CM bake refined", vertices, triangles, sphere)
    mesh.uv_layers.new(name=uv_map).data.foreach_set("uv", uv.astype(np.float32).ravel())
    return mesh


def _frame_attributes(mesh, uv_map):
    """Stores the tangent frame on the copy as corner attributes (the sign as a vector's x), so Cycles
    interpolates them per pixel as it does for its Normal Map node."""
    tangent, sign, normal = _tangent_frames(mesh, uv_map)
    for name, values in ((FRAME_TANGENT, tangent), (FRAME_NORMAL, normal),
                         (FRAME_SIGN, np.column_stack([sign, np.zeros((len(sign), 2))]))):
        mesh.attributes.new(name, 'FLOAT_VECTOR', 'CORNER').data.foreach_set(
            "vector", values.astype(np.float32).ravel())


def _tangent_space(normals, tangents, signs, frame_normals):
    """Inverts Blender's tangent-space decoding n = normalize(x T + y s (N x T) + z N) (T, N interpolated,
    not normalized): the unit (x, y, z) per row giving the object-space normals."""
    frames = np.stack([tangents, signs[:, None] * np.cross(frame_normals, tangents), frame_normals], axis=2)
    usable = np.abs(np.linalg.det(frames)) > 1e-8
    result = np.tile([0.0, 0.0, 1.0], (len(normals), 1))
    result[usable] = np.linalg.solve(frames[usable], normals[usable][:, :, None])[:, :, 0]
    return result / np.maximum(np.linalg.norm(result, axis=1, keepdims=True), 1e-12)


def bake_normals(source, target, size=1024, margin=16, align='features', progress=None):
    """A new image (size x size, Non-Color) holding source's normals as a tangent-space normal map in
    target's active UV layout, through the common map; raises maps.MapError (nothing created or modified)
    when it cannot be baked. progress(fraction) is called as the steps (four Cycles bakes, then the
    source's normals) finish."""
    found = _normal_problems(source, target, size, align)
    if found:
        raise maps.MapError("\n".join(found))
    rotation = _normal_rotation(source, target, align)
    uv_map = target.data.uv_layers.active.name
    pair = results.pair_map(target.data) is not None
    steps = _Steps(progress, 5)
    baked = {}
    with _baking_copy(target) as (_, mesh):
        _frame_attributes(mesh, uv_map)
        names = (FRAME_TANGENT, FRAME_NORMAL, FRAME_SIGN)
        if pair:
            centre, half = _image_attribute(mesh, source, target)
            names += (IMAGE_ATTRIBUTE,)
        for name in names:
            baked[name] = _bake_attribute(mesh, name, size, margin)
            steps.done()
    if pair:
        # Interpolated unit normals; cleared pixels decode to length 1.73.
        covered = np.abs(np.linalg.norm(baked[FRAME_NORMAL], axis=1) - 1) < 0.3
        landing = _nearest_on(source, centre + half * baked[IMAGE_ATTRIBUTE][covered])
    else:
        with _baking_copy(target, _refined_copy(target, uv_map)) as (_, mesh):
            directions = _bake_attribute(mesh, SPHERE_ATTRIBUTE, size, margin)
            steps.done()
        length = np.linalg.norm(directions, axis=1)
        covered = np.abs(length - 1) < 0.3  # interpolated unit vectors, as above
        landing = mapping.land(maps.parameterization(source), directions[covered] / length[covered, None])
    tangents, normals = baked[FRAME_TANGENT][covered], baked[FRAME_NORMAL][covered]
    signs = np.where(baked[FRAME_SIGN][covered, 0] < 0, -1.0, 1.0)
    wanted = _source_normals_at(source, landing, rotation)
    pixels = np.tile(np.array([0.5, 0.5, 1.0, 1.0], dtype=np.float32), (size * size, 1))
    pixels[covered, :3] = _tangent_space(wanted, tangents, signs, normals) * 0.5 + 0.5
    result = bpy.data.images.new(f"{target.name} normals from {source.name}", size, size, alpha=False)
    result.colorspace_settings.name = 'Non-Color'
    result.pixels.foreach_set(pixels.ravel())
    result.update()
    steps.done()
    return result
