"""Registers the add-on from one list of classes, plus its properties, handlers and overlay."""
import bpy
from bpy.app.handlers import persistent

from . import (features, operators_compute, operators_features, operators_preview, operators_set, overlay,
               panels, properties)

CLASSES = (
    properties.CLASSES
    + operators_set.CLASSES
    + operators_features.CLASSES
    + operators_compute.CLASSES
    + operators_preview.CLASSES
    + panels.CLASSES
)


@persistent
def _forget_cached_features(*_args):
    features.invalidate()


HANDLERS = (bpy.app.handlers.depsgraph_update_post, bpy.app.handlers.load_post, bpy.app.handlers.undo_post,
            bpy.app.handlers.redo_post)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    properties.attach()
    for handlers in HANDLERS:
        handlers.append(_forget_cached_features)
    overlay.install()


def unregister():
    overlay.uninstall()
    for handlers in HANDLERS:
        if _forget_cached_features in handlers:
            handlers.remove(_forget_cached_features)
    properties.detach()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    features.invalidate()
