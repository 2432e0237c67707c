"""Consistent Maps: put meshes into correspondence through spherical parameterizations, in Blender.

The package imports in plain Python too: bpy is only imported by register() and
unregister() (through `registration`), so the native core and the pure-Python
parts can be used and tested outside Blender. Scripts use `consistent_maps.api`.
"""

bl_info = {
    "name": "Consistent Maps",
    "author": "Consistent Maps developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Consistent Maps",
    "description": "Feature points, spherical parameterizations and correspondence between meshes",
    "category": "Mesh",
}


def register():
    from . import registration
    registration.register()


def unregister():
    from . import registration
    registration.unregister()
