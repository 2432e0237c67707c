"""Computed results, stored in the .blend.

On each mesh: the sphere coordinates of its vertices as a FLOAT_VECTOR point
attribute; as custom properties the fingerprint of the mesh they were computed
from (an edited mesh no longer matches: the result is stale), the numbers of the
computation, the token of the set computation it belongs to, and a reference to
its parameterized surface, a hidden mesh (the map is piecewise linear on a
refinement of the input: input vertices, then Steiner vertices) whose own
attribute holds the sphere position of each of its vertices, and whose refinement
attributes tie it to the input: the input triangle each of its faces lies in, and
each of its vertices as a weighted sum of (at most three) input vertices. On the
scene: the set's token and its feature locations on the sphere, by name.

Two objects of equal genus >= 1 have no sphere: each stores instead, per vertex,
the triangle of its partner's loop triangles it maps into and the barycentric
weights there (two point attributes), the same per corner (loop) for a point of
its face next to the corner (two corner attributes: per-corner values such as
UVs are taken from the corner's own side of a seam), with the same fingerprint,
numbers and token.
"""
import numpy as np

ATTRIBUTE = "cm_sphere"
FINGERPRINT = "cm_fingerprint"
STATS = "cm_stats"
SET = "cm_set"
SURFACE = "cm_surface"
LOCATIONS = "cm_feature_locations"
INPUT_TRIANGLE = "cm_input_triangle"
INPUT_VERTEX = "cm_input_vertex_{}"  # three INT point attributes, -1 for an unused slot
INPUT_WEIGHTS = "cm_input_weights"
PAIR_TRIANGLE = "cm_pair_triangle"  # INT point attribute: the partner's loop triangle
PAIR_WEIGHTS = "cm_pair_weights"    # FLOAT_VECTOR point attribute: barycentric weights in it
PAIR_CORNER_TRIANGLE = "cm_pair_corner_triangle"  # INT corner attribute: the same for each corner
PAIR_CORNER_WEIGHTS = "cm_pair_corner_weights"    # FLOAT_VECTOR corner attribute
PAIR_ATTRIBUTES = (PAIR_TRIANGLE, PAIR_WEIGHTS, PAIR_CORNER_TRIANGLE, PAIR_CORNER_WEIGHTS)

NONE, CURRENT, STALE = "NONE", "CURRENT", "STALE"


def _remove(mesh, *names):
    for name in names:
        old = mesh.attributes.get(name)
        if old is not None:
            mesh.attributes.remove(old)


def _write_sphere(mesh, sphere):
    _remove(mesh, ATTRIBUTE)
    attribute = mesh.attributes.new(ATTRIBUTE, 'FLOAT_VECTOR', 'POINT')
    attribute.data.foreach_set("vector", np.ascontiguousarray(sphere, dtype=np.float32).ravel())


def _write(mesh, name, kind, domain, field, values):
    mesh.attributes.new(name, kind, domain).data.foreach_set(field, np.ascontiguousarray(values).ravel())


def _write_refinement(surface, input_count, input_triangle, steiner_vertices, steiner_weights):
    """Input vertex i is itself (weight 1); Steiner vertex input_count + i lies at its weighted input vertices."""
    vertices = np.vstack([np.column_stack([np.arange(input_count), np.full((input_count, 2), -1)]),
                          np.asarray(steiner_vertices).reshape(-1, 3)]).astype(np.int32)
    weights = np.vstack([np.repeat([[1.0, 0.0, 0.0]], input_count, axis=0),
                         np.asarray(steiner_weights, dtype=float).reshape(-1, 3)]).astype(np.float32)
    _write(surface, INPUT_TRIANGLE, 'INT', 'FACE', "value", np.asarray(input_triangle, dtype=np.int32))
    for k in range(3):
        _write(surface, INPUT_VERTEX.format(k), 'INT', 'POINT', "value", vertices[:, k])
    _write(surface, INPUT_WEIGHTS, 'FLOAT_VECTOR', 'POINT', "vector", weights)


def surface_mesh(name, vertices, triangles, sphere):
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


def _store_common(mesh, fingerprint, stats, token):
    mesh[FINGERPRINT] = fingerprint
    mesh[STATS] = {k: v for k, v in stats.items() if isinstance(v, (bool, int, float, str))}
    mesh[SET] = token


def _drop_surface(mesh):
    import bpy
    old = mesh.get(SURFACE)
    if SURFACE in mesh:
        del mesh[SURFACE]
    if old is not None and old.users <= 1:  # only the fake user is left
        bpy.data.meshes.remove(old)


def store(mesh, sphere, fingerprint, stats, surface, refinement, token):
    """Stores one member's result; surface = (vertices, triangles, sphere) of its parameterized surface,
    refinement = (input triangle of each surface face, Steiner vertices (s, 3), Steiner weights (s, 3))."""
    _drop_surface(mesh)
    _remove(mesh, *PAIR_ATTRIBUTES)
    _write_sphere(mesh, sphere)
    _store_common(mesh, fingerprint, stats, token)
    mesh[SURFACE] = surface_mesh(mesh.name, *surface)
    _write_refinement(mesh[SURFACE], len(sphere), *refinement)


def store_pair(mesh, triangle, weights, corner_triangle, corner_weights, fingerprint, stats, token):
    """Stores one object's map onto its partner (genus >= 1): per vertex, then per corner (loop), the
    partner's loop triangle and barycentric weights."""
    _drop_surface(mesh)
    _remove(mesh, ATTRIBUTE, *PAIR_ATTRIBUTES)
    _write(mesh, PAIR_TRIANGLE, 'INT', 'POINT', "value", np.asarray(triangle, dtype=np.int32))
    _write(mesh, PAIR_WEIGHTS, 'FLOAT_VECTOR', 'POINT', "vector", np.asarray(weights, dtype=np.float32))
    _write(mesh, PAIR_CORNER_TRIANGLE, 'INT', 'CORNER', "value", np.asarray(corner_triangle, dtype=np.int32))
    _write(mesh, PAIR_CORNER_WEIGHTS, 'FLOAT_VECTOR', 'CORNER', "vector",
           np.asarray(corner_weights, dtype=np.float32))
    _store_common(mesh, fingerprint, stats, token)


def _pair_points(mesh, triangle_name, weights_name):
    triangle = _read(mesh.attributes, triangle_name, "value", np.int32, 1)
    weights = _read(mesh.attributes, weights_name, "vector", np.float32, 3)
    if triangle is None or weights is None:
        return None
    weights = weights.astype(np.float64)
    return triangle, weights / weights.sum(axis=1, keepdims=True)


def pair_map(mesh):
    """(triangle (n,), weights (n, 3)) of a mesh mapped directly onto its partner, or None."""
    return _pair_points(mesh, PAIR_TRIANGLE, PAIR_WEIGHTS)


def pair_corner_map(mesh):
    """(triangle (loops,), weights (loops, 3)): where a point of each corner's face next to it lands on the
    partner, for a mesh mapped directly onto it; None otherwise (or for a result stored before these)."""
    return _pair_points(mesh, PAIR_CORNER_TRIANGLE, PAIR_CORNER_WEIGHTS)


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


def _read(attributes, name, field, dtype, width):
    attribute = attributes.get(name)
    if attribute is None:
        return None
    values = np.empty(len(attribute.data) * width, dtype=dtype)
    attribute.data.foreach_get(field, values)
    return values.reshape(-1, width) if width > 1 else values


def refinement(mesh):
    """(input triangle of each surface face (m',), input vertices (N, 3) int, weights (N, 3)) of the mesh's
    parameterized surface: surface vertex i lies at sum_k weights[i, k] * input vertex vertices[i, k]
    (-1: unused). None when the surface or its refinement (results older than this) is missing."""
    stored = mesh.get(SURFACE)
    if stored is None:
        return None
    attributes = stored.attributes
    parts = [_read(attributes, INPUT_TRIANGLE, "value", np.int32, 1),
             *(_read(attributes, INPUT_VERTEX.format(k), "value", np.int32, 1) for k in range(3)),
             _read(attributes, INPUT_WEIGHTS, "vector", np.float32, 3)]
    if any(part is None for part in parts):
        return None
    return parts[0], np.column_stack(parts[1:4]), parts[4].astype(np.float64)


def stats(mesh):
    return dict(mesh[STATS]) if STATS in mesh else {}


def set_token(id_block):
    return id_block.get(SET)


def feature_locations(scene):
    """{name: (x, y, z)} of the set last computed in this scene."""
    return {name: tuple(location) for name, location in scene.get(LOCATIONS, {}).items()}


def state(mesh, current_fingerprint):
    """NONE (never computed), CURRENT, or STALE (the mesh changed since)."""
    if (mesh.attributes.get(ATTRIBUTE) is None and mesh.attributes.get(PAIR_TRIANGLE) is None) \
            or FINGERPRINT not in mesh:
        return NONE
    return CURRENT if mesh[FINGERPRINT] == current_fingerprint else STALE
