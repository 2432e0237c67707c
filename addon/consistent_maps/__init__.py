"""Consistent Maps: stretch-minimizing spherical parameterization of meshes, for Blender.

The package imports in plain Python as well (bpy is only imported inside
register/unregister), so the native core can be used and tested outside Blender:

    from consistent_maps import _native
"""

bl_info = {
    "name": "Consistent Maps",
    "author": "Consistent Maps developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Consistent Maps",
    "description": "Bijective, stretch-minimizing maps of closed genus-0 meshes onto the sphere",
    "category": "Mesh",
}


def register():
    import bpy  # noqa: F401  (Blender only; the UI is registered here as it grows)


def unregister():
    import bpy  # noqa: F401
