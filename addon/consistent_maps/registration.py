"""Registers the add-on from one list of classes, plus its properties, handlers and overlay."""
import bpy
from bpy.app.handlers import persistent

from . import (features, job, operators_compute, operators_database, operators_distortion, operators_features,
               operators_morph, operators_preview, operators_remesh, operators_set, operators_transfer, overlay, panels,
               properties)

CLASSES = (
    properties.CLASSES
    + operators_set.CLASSES
    + operators_features.CLASSES
    + operators_compute.CLASSES
    + operators_preview.CLASSES
    + operators_remesh.CLASSES
    + operators_morph.CLASSES
    + operators_transfer.CLASSES
    + operators_distortion.CLASSES
    + operators_database.CLASSES
    + panels.CLASSES
)


@persistent
def _forget_cached_features(*_args):
    features.invalidate()


@persistent
def _drop_running_job(*_args):
    """Loading a file ends the Compute operator: stop its computation, whose objects are gone."""
    if job.current() is not None:
        job.current().cancel()
        job.finish()


HANDLERS = (bpy.app.handlers.depsgraph_update_post, bpy.app.handlers.load_post, bpy.app.handlers.undo_post,
            bpy.app.handlers.redo_post)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    properties.attach()
    for handlers in HANDLERS:
        handlers.append(_forget_cached_features)
    features.use_cache(True)
    bpy.app.handlers.load_pre.append(_drop_running_job)
    overlay.install()


def unregister():
    overlay.uninstall()
    _drop_running_job()
    if _drop_running_job in bpy.app.handlers.load_pre:
        bpy.app.handlers.load_pre.remove(_drop_running_job)
    for handlers in HANDLERS:
        if _forget_cached_features in handlers:
            handlers.remove(_forget_cached_features)
    properties.detach()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    features.use_cache(False)
