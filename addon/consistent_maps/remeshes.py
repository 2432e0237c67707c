"""Consistent remeshes as new objects: one shared connectivity, features at identical vertex indices.

They go into the collection "Consistent Maps", each with its original's transform; the
originals are not touched.
"""
import bpy

from . import features

COLLECTION = "Consistent Maps"
PAIR_REMESH = "cm_pair_remesh"  # custom property of a pair's remeshes: the carrier's name, folded triangles


def collection(scene):
    """The collection "Consistent Maps" (created and linked to the scene when missing)."""
    found = bpy.data.collections.get(COLLECTION) or bpy.data.collections.new(COLLECTION)
    if scene.collection.children.get(found.name) is None:
        scene.collection.children.link(found)
    return found


def create(scene, objects, remeshed, names, pair=None):
    """New objects from the native consistent_remesh (or remesh_pair) result (same order as objects); `pair`
    (a pair's remeshes: {"carrier": name, "folded_triangles": count}) is kept on each as PAIR_REMESH."""
    target = collection(scene)
    triangles = remeshed["triangles"].tolist()
    created = []
    for obj, positions in zip(objects, remeshed["positions"]):
        mesh = bpy.data.meshes.new(f"{obj.name} remesh")
        mesh.from_pydata(positions.tolist(), [], triangles)
        mesh.update()
        new = bpy.data.objects.new(mesh.name, mesh)
        new.matrix_world = obj.matrix_world.copy()
        if pair is not None:
            new[PAIR_REMESH] = pair
        for name, vertex in zip(names, remeshed["feature_vertices"]):
            new.vertex_groups.new(name=features.group_name(name)).add([int(vertex)], 1.0, 'REPLACE')
        target.objects.link(new)
        created.append(new)
    features.invalidate()
    return created
