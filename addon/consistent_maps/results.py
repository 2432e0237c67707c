"""Computed results, stored in the .blend.

On each mesh: the sphere coordinates of its vertices as a FLOAT_VECTOR point
attribute; as custom properties the fingerprint of the mesh they were computed
from (an edited mesh no longer matches: the result is stale), the numbers of the
computation, the token of the set computation it belongs to, and a reference to
its parameterized surface, a hidden mesh (the map is piecewise linear on a
refinement of the input: input vertices, then Steiner vertices) whose own
attribute holds the sphere position of each of its vertices. On the scene: the
set's token and its feature locations on the sphere, by name.
"""
import numpy as np

ATTRIBUTE = "cm_sphere"
FINGERPRINT = "cm_fingerprint"
STATS = "cm_stats"
SET = "cm_set"
SURFACE = "cm_surface"
LOCATIONS = "cm_feature_locations"

NONE, CURRENT, STALE = "NONE", "CURRENT", "STALE"


def _write_sphere(mesh, sphere):
    old = mesh.attributes.get(ATTRIBUTE)
    if old is not None:
        mesh.attributes.remove(old)
    attribute = mesh.attributes.new(ATTRIBUTE, 'FLOAT_VECTOR', 'POINT')
    attribute.data.foreach_set("vector", np.ascontiguousarray(sphere, dtype=np.float32).ravel())


def _surface_mesh(name, vertices, triangles, sphere):
    import bpy
    surface = bpy.data.meshes.new(f"CM surface {name}")
    surface.vertices.add(len(vertices))
    surface.vertices.foreach_set("co", np.ascontiguousarray(vertices, dtype=np.float32).ravel())
    surface.loops.add(3 * len(triangles))
    surface.loops.foreach_set("vertex_index", np.ascontiguousarray(triangles, dtype=np.int32).ravel())
    surface.polygons.add(len(triangles))
    surface.polygons.foreach_set("loop_start", np.arange(0, 3 * len(triangles), 3, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):
        surface.polygons.foreach_set("loop_total", np.full(len(triangles), 3, dtype=np.int32))
    surface.update()
    _write_sphere(surface, sphere)
    surface.use_fake_user = True  # kept in the .blend although no object uses it
    return surface


def store(mesh, sphere, fingerprint, stats, surface, token):
    """Stores one member's result; surface = (vertices, triangles, sphere) of its parameterized surface."""
    import bpy
    old = mesh.get(SURFACE)
    _write_sphere(mesh, sphere)
    mesh[FINGERPRINT] = fingerprint
    mesh[STATS] = {k: v for k, v in stats.items() if isinstance(v, (bool, int, float, str))}
    mesh[SET] = token
    mesh[SURFACE] = _surface_mesh(mesh.name, *surface)
    if old is not None and old.users <= 1:  # only the fake user is left
        bpy.data.meshes.remove(old)


def store_set(scene, token, names, locations):
    scene[SET] = token
    scene[LOCATIONS] = {name: [float(x) for x in location] for name, location in zip(names, locations)}


def sphere(mesh):
    """(n, 3) float32 sphere coordinates, or None if the mesh has no result."""
    attribute = mesh.attributes.get(ATTRIBUTE)
    if attribute is None or attribute.domain != 'POINT' or attribute.data_type != 'FLOAT_VECTOR':
        return None
    values = np.empty(len(attribute.data) * 3, dtype=np.float32)
    attribute.data.foreach_get("vector", values)
    return values.reshape(-1, 3)


def surface(mesh):
    """(vertices, triangles, sphere) of the mesh's parameterized surface, or None."""
    stored = mesh.get(SURFACE)
    if stored is None:
        return None
    vertices = np.empty(len(stored.vertices) * 3, dtype=np.float32)
    stored.vertices.foreach_get("co", vertices)
    triangles = np.empty(len(stored.loops), dtype=np.int32)
    stored.loops.foreach_get("vertex_index", triangles)
    return vertices.reshape(-1, 3).astype(np.float64), triangles.reshape(-1, 3), sphere(stored).astype(np.float64)


def stats(mesh):
    return dict(mesh[STATS]) if STATS in mesh else {}


def set_token(id_block):
    return id_block.get(SET)


def feature_locations(scene):
    """{name: (x, y, z)} of the set last computed in this scene."""
    return {name: tuple(location) for name, location in scene.get(LOCATIONS, {}).items()}


def state(mesh, current_fingerprint):
    """NONE (never computed), CURRENT, or STALE (the mesh changed since)."""
    if mesh.attributes.get(ATTRIBUTE) is None or FINGERPRINT not in mesh:
        return NONE
    return CURRENT if mesh[FINGERPRINT] == current_fingerprint else STALE
