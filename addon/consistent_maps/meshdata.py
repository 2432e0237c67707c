"""Copies a Blender mesh out as numpy arrays, and fingerprints it.

The original mesh (obj.data, no modifiers) is used, because feature vertex
groups and stored results refer to its vertex indices. N-gons are split by
Blender's own loop triangulation, whose triangles index the original vertices:
row i of any per-vertex result belongs to original vertex i, whatever the
polygons were.
"""
import hashlib
from dataclasses import dataclass

import numpy as np


@dataclass
class MeshArrays:
    vertices: np.ndarray           # (n, 3) float64, object space
    triangles: np.ndarray          # (m, 3) int32, indices into vertices
    fingerprint: str
    corners: np.ndarray            # (m, 3) int32, the loop of each triangle corner


def fingerprint(mesh):
    """Hash of the vertex positions and the polygon connectivity: changes when the mesh is edited."""
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    loops = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", loops)
    sizes = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_total", sizes)
    digest = hashlib.sha1()
    for part in (np.array([len(co), len(loops), len(sizes)], dtype=np.int64), co, loops, sizes):
        digest.update(part.tobytes())
    return digest.hexdigest()


def loop_triangles(mesh):
    """(vertices (m, 3), corners (m, 3)) int32 of the mesh's loop triangles: Blender's triangulation,
    indexing the original vertices and loops."""
    mesh.calc_loop_triangles()
    vertices = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("vertices", vertices)
    corners = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int32)
    mesh.loop_triangles.foreach_get("loops", corners)
    return vertices.reshape(-1, 3), corners.reshape(-1, 3)


def loop_corners(corners):
    """Per loop: one loop triangle corner holding it (index 3 t + k), from loop_triangles' corners (every
    loop is in at least one loop triangle)."""
    first = np.empty(int(corners.max()) + 1 if corners.size else 0, dtype=np.int64)
    first[corners.ravel()] = np.arange(corners.size)
    return first


def _positions(mesh):
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", co)
    return co.reshape(-1, 3).astype(np.float64)


def arrays(mesh):
    """(vertices (n, 3) float64, triangles (m, 3) int32) of the mesh as stored (no Edit Mode sync)."""
    return _positions(mesh), loop_triangles(mesh)[0]


def extract(obj):
    """MeshArrays of a mesh object, Edit Mode changes included."""
    if obj.mode == 'EDIT':
        obj.update_from_editmode()
    triangles, corners = loop_triangles(obj.data)
    return MeshArrays(_positions(obj.data), triangles, fingerprint(obj.data), corners)
