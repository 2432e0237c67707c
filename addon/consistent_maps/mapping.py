"""Maps between members of a consistent set, through their common sphere.

A point of member A is its sphere direction; located in member B's parameterization
(the native SphereLocator on B's refined sphere) it gives B's refined triangle and
barycentric coordinates, which the refinement (input triangle of each refined
triangle, each refined vertex as weighted input vertices) turns into B's input
triangle and barycentric coordinates with respect to its corners. Per-vertex and
per-corner values of B are interpolated there. Array glue only, no bpy: the
geometry is the native library's.
"""
from dataclasses import dataclass

import numpy as np

from . import native

# How far a corner's sample point moves from its vertex into the corner's own triangle
# (barycentric weight given to each of the two other corners): enough to pick the
# triangle's side of a seam, too little to change interpolated values measurably.
CORNER_NUDGE = 1e-3


@dataclass
class Parameterization:
    """One member's stored map, over its input triangulation."""
    sphere: np.ndarray            # (N, 3) refined sphere: input vertices first, then Steiner vertices
    triangles: np.ndarray         # (M', 3) refined triangles
    input_triangle: np.ndarray    # (M',) the input triangle each refined triangle lies in
    input_vertices: np.ndarray    # (N, 3) refined vertex i lies at sum_k input_weights[i, k] * input vertex
    input_weights: np.ndarray     # (N, 3)   input_vertices[i, k] (-1: unused slot, weight 0)
    input_triangles: np.ndarray   # (M, 3) the input (Blender loop) triangles


@dataclass
class Landing:
    """Where points land on a member: input triangle and barycentric coordinates w.r.t. its corners."""
    triangle: np.ndarray      # (q,)
    barycentric: np.ndarray   # (q, 3)


def refined_in_input(parameterization):
    """(M', 3, 3): row j of matrix r gives refined triangle r's corner j in barycentric coordinates of the
    input triangle it lies in, so refined barycentric b becomes b @ matrix."""
    p = parameterization
    sources = p.input_vertices[p.triangles]                             # (M', 3, 3) input vertices
    own = p.input_triangles[p.input_triangle]                           # (M', 3) input corners
    matches = sources[:, :, :, None] == own[:, None, None, :]           # (M', corner, slot, input corner)
    return (p.input_weights[p.triangles][:, :, :, None] * matches).sum(axis=2)


def land(parameterization, directions, *, threads=2):
    """Where the sphere directions (q, 3) land on the member's input triangles."""
    p = parameterization
    refined, weights = native.sphere_locator(p.sphere, p.triangles).locate(directions, threads=threads)
    matrices = refined_in_input(p)  # gathered one column at a time: far faster than whole (q, 3, 3) matrices
    barycentric = np.column_stack([sum(weights[:, j] * matrices[:, j, k][refined] for j in range(3))
                                   for k in range(3)])
    barycentric = np.clip(barycentric, 0, None)
    barycentric /= barycentric.sum(axis=1, keepdims=True)
    return Landing(p.input_triangle[refined], barycentric)


def at_vertices(landing, triangles, values):
    """Per-vertex values (n,) or (n, d) of the member interpolated at the landing points."""
    values = np.asarray(values, dtype=np.float64)
    corners = triangles[landing.triangle]                               # (q, 3)
    weights = landing.barycentric if values.ndim == 1 else landing.barycentric[:, :, None]
    return sum(weights[:, j] * values[corners[:, j]] for j in range(3))  # a corner at a time: fast gathers


def at_corners(landing, triangle_corners, values):
    """Per-corner values (c,) or (c, d) interpolated at the landing points; triangle_corners (M, 3) are
    the corners (Blender loops) of each input triangle, so a value comes from the triangle the point
    lies in: values differing across a seam are taken from the right side."""
    return at_vertices(landing, triangle_corners, values)


def at_corners_in_face_charts(landing, triangles, triangle_corners, uv, reference):
    """Texture coordinates uv (c, 2) of the member's corners interpolated at the landing points like
    at_corners, then each point's re-expressed in the chart of point reference[i] (e.g. the first corner of
    the same face), continued across the member's UV seams: a face whose image straddles a seam keeps
    coordinates continuing across it (u > 1, say) instead of spanning the whole texture."""
    values = at_corners(landing, triangle_corners, uv)
    return native.continue_across_seams(triangles, triangle_corners, np.asarray(uv, dtype=np.float64),
                                        landing.triangle, values, reference)


def corner_directions(parameterization):
    """(M, 3, 3) sphere direction of each corner of each input triangle, moved by CORNER_NUDGE into a
    refined triangle of that input triangle incident to the corner's vertex (the map is linear there),
    so that locating it elsewhere picks the corner's own side of a seam. A corner of a triangle with no
    refined triangle at its vertex (zero area) keeps its vertex's direction."""
    p = parameterization
    count = np.int64(len(p.sphere))
    keys = (np.repeat(p.input_triangle.astype(np.int64), 3) * count + p.triangles.ravel())
    order = np.argsort(keys, kind="stable")
    wanted = (np.arange(len(p.input_triangles), dtype=np.int64)[:, None] * count + p.input_triangles).ravel()
    found = np.minimum(np.searchsorted(keys[order], wanted), len(keys) - 1)
    hit = keys[order][found] == wanted
    refined, corner = np.divmod(order[found], 3)
    ring = p.triangles[refined][:, [0, 1, 2, 0, 1]]                     # cyclic, so corner..corner+2
    rows = np.arange(len(wanted))
    nudged = ((1 - 2 * CORNER_NUDGE) * p.sphere[ring[rows, corner]]
              + CORNER_NUDGE * (p.sphere[ring[rows, corner + 1]] + p.sphere[ring[rows, corner + 2]]))
    directions = np.where(hit[:, None], nudged, p.sphere[p.input_triangles.ravel()])
    return directions.reshape(-1, 3, 3)
