"""The one place the add-on calls the native library.

Every geometric computation lives in C++ (`_native`); this module only adapts
arguments and names. Capabilities the library gains later (parameterization
constrained by features, remeshing on the octahedral grid, point location on
the sphere) get their wrapper here, next to the ones that exist today.
No bpy here: it runs in worker threads and in plain Python.
"""
from . import _native

InvalidMeshError = _native.InvalidMeshError
Cancelled = _native.Cancelled


def check_mesh(vertices, triangles):
    """Topology report of a triangle mesh (dict); 'sphere_error' is None when it can be mapped."""
    return _native.check_mesh(vertices, triangles)


def spherical_parameterization(vertices, triangles, *, effort, seed, threads, progress):
    """Unconstrained stretch-minimizing map onto the unit sphere: (sphere (n, 3), stats dict).

    progress(fraction, stage) -> bool is called from the computation; False cancels it
    (raises Cancelled). Raises InvalidMeshError when the mesh cannot be mapped.
    """
    return _native.spherical_parameterization(
        vertices, triangles, effort=effort, seed=seed, threads=threads, progress=progress)
