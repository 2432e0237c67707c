"""The one place the add-on calls the native library.

Every geometric computation lives in C++ (`_native`); this module only adapts
arguments and names, so a capability the library gains (e.g. point location on
the sphere for transfers) gets its wrapper here. No bpy here: it runs in worker
threads and in plain Python.
"""
from . import _native

InvalidMeshError = _native.InvalidMeshError
Cancelled = _native.Cancelled


def check_mesh(vertices, triangles):
    """Topology report of a triangle mesh (dict); 'sphere_error' is None when it can be mapped to the sphere,
    'pair_map_error' when it can be mapped onto a partner of its genus."""
    return _native.check_mesh(vertices, triangles)


def spherical_parameterization(vertices, triangles, *, effort, seed, threads, progress):
    """Unconstrained stretch-minimizing map onto the unit sphere: (sphere (n, 3), stats dict).

    progress(fraction, stage) -> bool is called from the computation; False cancels it
    (raises Cancelled). Raises InvalidMeshError when the mesh cannot be mapped.
    """
    return _native.spherical_parameterization(
        vertices, triangles, effort=effort, seed=seed, threads=threads, progress=progress)


def consistent_spherical_parameterization(meshes, features, *, effort, seed, threads, progress, restarts=1,
                                          align=False):
    """Maps of a set with every feature on one common sphere point (thesis 3.2), computed `restarts` times
    (seeds seed, seed + 1, ...) keeping the run whose maps keep most of each member's own efficiency;
    `align`: then each member's map refitted towards the first complete member's (step 7).

    meshes: [(vertices, triangles)]; features: (members, k) vertex indices. Returns a dict with
    'feature_locations' (k, 3) and 'members': per member (sphere, stats, extras), extras holding the
    map as a parameterized surface ('refined_vertices', 'triangles', 'refined_sphere').
    """
    return _native.consistent_spherical_parameterization(
        meshes, features, restarts=restarts, align=align, effort=effort, seed=seed, threads=threads,
        progress=progress)


def intersurface_map(mesh_a, mesh_b, feature_pairs, *, effort, seed, threads, progress, restarts=1,
                     corner_images=False):
    """The map between two meshes of equal genus, closed or with as many holes (genus >= 1: through a consistent partition,
    Schreiner et al.), each pair [vertex of A, vertex of B] exactly onto each other: a dict with per vertex
    of A its triangle of B and barycentric weights ('a_to_b_triangle', 'a_to_b_barycentric'), likewise
    'b_to_a_*', and 'genus', 'symmetric_dirichlet' (A to B, B to A), 'seconds'. Genus 0: the least
    distorted of `restarts` maps through the sphere and of the direct map ('method' says which was kept).
    The direct map of a pair without feature pairs and holes starts from the least distorted of 8 automatic
    first pairs mapped with their patches' areas matched but without the local sweeps (`restarts` of them
    optimized, the least distorted kept). corner_images: also per triangle corner (row 3 t + k) the image of a
    point of the triangle next to it ('a_corners_to_b_triangle', 'a_corners_to_b_barycentric',
    'b_corners_to_a_*'), for per-corner values such as UVs."""
    return _native.intersurface_map(mesh_a, mesh_b, feature_pairs, restarts=restarts, effort=effort, seed=seed,
                                    threads=threads, progress=progress, corner_images=corner_images)


def consistent_remesh(surfaces, feature_locations, resolution, *, threads):
    """Every (vertices, triangles, sphere) surface sampled on one octahedral grid of even resolution:
    dict with 'triangles' (shared), 'positions' (members, V, 3), 'sphere', 'feature_vertices' (k,)."""
    return _native.consistent_remesh(surfaces, feature_locations, resolution, threads=threads)


def remesh_pair(mesh_a, mesh_b, a_to_b, b_to_a, feature_pairs, target_vertices):
    """Consistent remeshes of two meshes mapped onto each other: one of them simplified to target_vertices
    (or as far as it goes without folding a triangle), its vertices' images giving the other's. mesh_*:
    (vertices, triangles); a_to_b, b_to_a: (triangles, barycentric) of each vertex's image; feature_pairs (k, 2).
    Dict with 'triangles' (shared), 'a_positions', 'b_positions', 'feature_vertices' (k,), 'folded_triangles'."""
    return _native.remesh_pair(mesh_a, mesh_b, a_to_b, b_to_a, feature_pairs, target_vertices)


def map_distortion(source, target, image):
    """Per source triangle, how the map image = (triangles, barycentric) of source's vertices on target
    distorts it: dict of 'symmetric_dirichlet' (optimum 4), 'flipped' (bool) and 'area' per triangle, and their
    'mean', 'median' and 'folded' count."""
    return _native.map_distortion(source, target, image)


def sphere_locator(sphere, triangles):
    """Point location on a parameterization given as a triangulated sphere (covering it once): the object's
    locate(directions, threads=) gives (triangles (q,), barycentric (q, 3)) of each direction."""
    return _native.SphereLocator(sphere, triangles)


def surface_locator(vertices, triangles):
    """Closest points on a triangle mesh: the object's locate(points, threads=) gives (triangles (q,),
    barycentric (q, 3), distances (q,)) of the surface point nearest each point."""
    return _native.SurfaceLocator(vertices, triangles)


def continue_across_seams(triangles, triangle_uvs, uvs, point_triangles, values, reference):
    """Texture coordinates values (q, 2) of points on triangles (m, 3) (corner k of triangle t has
    uvs[triangle_uvs[t, k]]), point i's computed in its triangle point_triangles[i]'s chart, returned in the
    chart of point reference[i]'s triangle: continued across the seams between them."""
    return _native.continue_across_seams(triangles, triangle_uvs, uvs, point_triangles, values, reference)
