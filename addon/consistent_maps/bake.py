"""Texture transfer: the source's image texture baked into the target's own UV layout through the map.

The target's corners get, through the map, the source UV they land on (seam-aware, as
in transfer); a temporary copy of the target, whose material shows the source image
at those UVs as emission, is baked by Cycles into a new image in the target's UV
layout (Blender rasterizes and pads the seams). The target itself is not modified.
"""
import bpy
import numpy as np

from . import mapping, maps, meshdata

SOURCE_UV = "cm_bake_source_uv"


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


def _problems(source, target, size):
    found = maps.problems([source, target])
    if found:
        return found
    texture = source_image(source)
    if texture is None:
        found.append(f"'{source.name}' has no image texture in its materials: nothing to bake")
    elif texture[1] is None:
        found.append(f"'{source.name}' has no UV map for its image texture")
    if not target.data.uv_layers:
        found.append(f"'{target.name}' has no UV map to bake into: unwrap it first (UV > Unwrap)")
    if not hasattr(bpy.context.scene, "cycles"):
        found.append("Baking needs the Cycles render engine: enable the Cycles add-on")
    if not 16 <= size <= 16384:
        found.append(f"The image size must be between 16 and 16384 pixels, not {size}")
    return found


def _emission_material(image):
    material = bpy.data.materials.new("CM bake")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    uv = nodes.new("ShaderNodeUVMap")
    uv.uv_map = SOURCE_UV
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    emission = nodes.new("ShaderNodeEmission")
    output = nodes.new("ShaderNodeOutputMaterial")
    links.new(uv.outputs["UV"], texture.inputs["Vector"])
    links.new(texture.outputs["Color"], emission.inputs["Color"])
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    return material, nodes


def bake(source, target, size=1024, margin=16):
    """A new image (size x size) of source's image texture in target's active UV layout; raises
    maps.MapError (nothing created or modified) when it cannot be baked."""
    found = _problems(source, target, size)
    if found:
        raise maps.MapError("\n".join(found))
    image, uv_map = source_image(source)
    layer_data = source.data.uv_layers[uv_map].data
    source_uv = np.empty(len(layer_data) * 2, dtype=np.float32)
    layer_data.foreach_get("uv", source_uv)
    uv = mapping.at_corners(maps.corner_landing(source, target), meshdata.loop_triangles(source.data)[1],
                            source_uv.reshape(-1, 2))
    result = bpy.data.images.new(f"{target.name} from {source.name}", size, size, alpha=False)
    scene, layer = bpy.context.scene, bpy.context.view_layer
    mesh = target.data.copy()
    mesh.uv_layers.new(name=SOURCE_UV).data.foreach_set("uv", uv.astype(np.float32).ravel())
    mesh.uv_layers.active = mesh.uv_layers[target.data.uv_layers.active.name]
    copy = bpy.data.objects.new("CM bake", mesh)
    copy.matrix_world = target.matrix_world.copy()
    scene.collection.objects.link(copy)
    material, nodes = _emission_material(image)
    mesh.materials.clear()
    mesh.materials.append(material)
    mesh.polygons.foreach_set("material_index", np.zeros(len(mesh.polygons), dtype=np.int32))
    mesh.update()
    bake_node = nodes.new("ShaderNodeTexImage")
    bake_node.image = result
    nodes.active = bake_node
    selected, active = list(bpy.context.selected_objects), layer.objects.active
    engine, samples, denoise = scene.render.engine, scene.cycles.samples, scene.cycles.use_denoising
    try:
        for obj in selected:
            obj.select_set(False)
        copy.select_set(True)
        layer.objects.active = copy
        scene.render.engine = 'CYCLES'
        scene.cycles.samples = 1
        scene.cycles.use_denoising = False  # nothing to denoise, and builds without OpenImageDenoise fail
        bpy.ops.object.bake(type='EMIT', margin=margin, use_clear=True)
    except RuntimeError as e:
        bpy.data.images.remove(result)
        raise maps.MapError(f"Baking failed: {e}") from e
    finally:
        scene.render.engine, scene.cycles.samples, scene.cycles.use_denoising = engine, samples, denoise
        bpy.data.objects.remove(copy)
        bpy.data.meshes.remove(mesh)
        bpy.data.materials.remove(material)
        for obj in selected:
            obj.select_set(True)
        layer.objects.active = active
    return result
