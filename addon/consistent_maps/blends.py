"""n-way blends of consistent remeshes (thesis Fig. 4.5): one object, a shape key per other member.

The new object "Blend" (in the collection "Consistent Maps") has the first remesh's
mesh as its basis and, for every other remesh, the key "→ <name>" with that remesh's
positions at the same vertex indices; mixing the key values blends the shapes.
"""
import numpy as np

from . import connectivity, features, maps, morphs


def create(objects):
    """The blend object of consistent remeshes (at least 2); raises RemeshSetError (nothing created)."""
    import bpy

    from . import remeshes  # Blender-only, like everything that creates data
    objects = list(objects)
    connectivity.check(objects, "Blends")
    mesh = objects[0].data.copy()  # the connectivity, and the features: vertex groups live on the mesh
    mesh.name = "Blend"
    obj = bpy.data.objects.new("Blend", mesh)
    obj.shape_key_clear()
    obj.shape_key_add(name="Basis", from_mix=False)
    for other in objects[1:]:
        key = obj.shape_key_add(name=morphs.key_name(other), from_mix=False)
        key.data.foreach_set("co", maps.positions(other.data).astype(np.float32).ravel())
    obj.matrix_world = objects[0].matrix_world.copy()
    remeshes.collection(bpy.context.scene).objects.link(obj)
    mesh.update()
    features.invalidate()
    return obj
