"""Viewport overlay: the features of the set as coloured points with their names.

A feature's colour follows from its name, so corresponding points have the same
colour on every object. Points follow the evaluated mesh (e.g. the sphere
preview). Nothing is drawn in background mode, where no viewport exists.
"""
import colorsys
import zlib

import bpy

from . import features
from .properties import set_objects

POINT_SIZE = 10.0
FONT_SIZE = 13

_handles = []


def colour(name):
    hue = (zlib.crc32(name.encode()) % 360) / 360
    return (*colorsys.hsv_to_rgb(hue, 0.8, 1.0), 1.0)


def feature_points(context):
    """[(world position, colour, label)] of the placed features of the set's visible objects."""
    depsgraph = context.evaluated_depsgraph_get()
    points = []
    for obj in set_objects(context.scene):
        if not obj.visible_get():
            continue
        placed = features.features(obj)
        if not placed:
            continue
        evaluated = obj.evaluated_get(depsgraph)
        mesh = evaluated.data if len(evaluated.data.vertices) == len(obj.data.vertices) else obj.data
        for name, index in placed.items():
            points.append((evaluated.matrix_world @ mesh.vertices[index].co, colour(name), name))
    return points


def _shown(context):
    return context.scene.consistent_maps.show_features and context.space_data.overlay.show_overlays


def _draw_points():
    import gpu
    from gpu_extras.batch import batch_for_shader
    context = bpy.context
    if not _shown(context):
        return
    points = feature_points(context)
    if not points:
        return
    try:  # point shaders with a size uniform replace point_size_set in newer Blender
        shader, sized = gpu.shader.from_builtin('POINT_FLAT_COLOR'), True
    except ValueError:
        shader, sized = gpu.shader.from_builtin('FLAT_COLOR' if bpy.app.version >= (4, 0, 0) else '3D_FLAT_COLOR'), False
    batch = batch_for_shader(shader, 'POINTS', {"pos": [p[0] for p in points], "color": [p[1] for p in points]})
    shader.bind()
    if sized:
        shader.uniform_float("size", POINT_SIZE)
    else:
        gpu.state.point_size_set(POINT_SIZE)
    gpu.state.depth_test_set('NONE')
    batch.draw(shader)
    gpu.state.point_size_set(1.0)


def _draw_names():
    import blf
    from bpy_extras.view3d_utils import location_3d_to_region_2d
    context = bpy.context
    if not _shown(context):
        return
    font = 0
    blf.size(font, FONT_SIZE)
    for position, rgba, name in feature_points(context):
        xy = location_3d_to_region_2d(context.region, context.region_data, position)
        if xy is not None:
            blf.color(font, *rgba)
            blf.position(font, xy.x + 8, xy.y + 4, 0)
            blf.draw(font, name)


def install():
    if bpy.app.background or _handles:
        return
    _handles.append((bpy.types.SpaceView3D.draw_handler_add(_draw_points, (), 'WINDOW', 'POST_VIEW'), 'WINDOW'))
    _handles.append((bpy.types.SpaceView3D.draw_handler_add(_draw_names, (), 'WINDOW', 'POST_PIXEL'), 'WINDOW'))


def uninstall():
    while _handles:
        handle, region = _handles.pop()
        bpy.types.SpaceView3D.draw_handler_remove(handle, region)
