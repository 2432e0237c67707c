"""Compute (modal, worker thread; synchronous in background mode) and Cancel."""
import bpy

from . import api, job
from .properties import set_objects

TIMER_STEP = 0.1


def _options(context):
    settings = context.scene.consistent_maps
    return {"effort": int(settings.effort), "restarts": settings.restarts, "align": settings.align,
            "pair_map": settings.pair_map}


def _leave_edit_mode(context, objects):
    if any(obj.mode == 'EDIT' for obj in objects) and context.mode == 'EDIT_MESH':
        bpy.ops.object.mode_set(mode='OBJECT')


def _summary(stats):
    first = next(iter(stats.values()))
    if "genus" in first:
        median = ", ".join(f"{s['median_symmetric_dirichlet']:.1f}" for s in stats.values())
        mean = ", ".join(f"{s['symmetric_dirichlet']:.1f}" for s in stats.values())
        way = "directly" if first.get("method") == "partition" else "through the sphere"
        # Folded samples: triangles that would show inverted at the end of a morph, though the map itself
        # (bijective: it folds nowhere) is continuous and one-to-one.
        folds = ", ".join(str(s.get("folded_samples", 0)) for s in stats.values())
        bijective = "bijective" if all(s.get("bijective") for s in stats.values()) else "FOLDED"
        return (f"Mapped 2 objects of genus {first['genus']} onto each other {way} in {first['seconds']:.1f} s "
                f"(symmetric Dirichlet median {median}, mean {mean}; best 4; the map {bijective}; triangles "
                f"folded at the morph's end {folds})")
    worst = min(s["efficiency"] for s in stats.values())
    seconds = sum(s["seconds"] for s in stats.values())
    return f"Mapped {len(stats)} object(s) onto the sphere in {seconds:.1f} s (lowest efficiency {worst:.3f})"


class CM_OT_compute(bpy.types.Operator):
    """Map every object of the set onto the sphere and store the results (Esc cancels)"""
    bl_idname = "consistent_maps.compute"
    bl_label = "Compute"
    bl_options = {'REGISTER', 'UNDO'}

    _timer = None
    _job = None

    @classmethod
    def poll(cls, context):
        return job.current() is None

    def _prepare(self, context):
        """(tasks, feature names) for the set, or None after reporting why it cannot be computed."""
        objects = set_objects(context.scene)
        _leave_edit_mode(context, objects)
        try:
            return api.prepare(objects, pair_map=context.scene.consistent_maps.pair_map), api.feature_names(objects)
        except api.ComputeError as e:
            self.report({'ERROR'}, str(e))
            return None

    def _finish(self, stats_or_error):
        if isinstance(stats_or_error, Exception):
            self.report({'ERROR'}, str(stats_or_error))
            return {'CANCELLED'}
        self.report({'INFO'}, _summary(stats_or_error))
        return {'FINISHED'}

    def execute(self, context):
        prepared = self._prepare(context)
        if prepared is None:
            return {'CANCELLED'}
        tasks, names = prepared
        try:
            return self._finish(api.apply(tasks, api.run(tasks, names, **_options(context))))
        except api.ComputeError as e:
            return self._finish(e)

    def invoke(self, context, event):
        if bpy.app.background:
            return self.execute(context)
        prepared = self._prepare(context)
        if prepared is None:
            return {'CANCELLED'}
        self._job = job.start(*prepared, _options(context))
        wm = context.window_manager
        wm.consistent_maps_progress = 0
        self._timer = wm.event_timer_add(TIMER_STEP, window=context.window)
        wm.modal_handler_add(self)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type == 'ESC' and event.value == 'PRESS':
            self._job.cancel()
            return {'RUNNING_MODAL'}
        if event.type != 'TIMER':
            return {'PASS_THROUGH'}
        wm = context.window_manager
        wm.consistent_maps_progress = 100 * self._job.fraction
        context.workspace.status_text_set(
            f"Consistent Maps: {100 * self._job.fraction:.0f} %  {self._job.stage}   (Esc to cancel)")
        for area in context.screen.areas:
            if area.type == 'VIEW_3D':
                area.tag_redraw()
        if not self._job.done:
            return {'RUNNING_MODAL'}
        wm.event_timer_remove(self._timer)
        context.workspace.status_text_set(None)
        finished = self._job
        job.finish()
        if finished.cancelled:
            self.report({'WARNING'}, "Computation cancelled: nothing was changed")
            return {'CANCELLED'}
        if finished.error is not None:
            return self._finish(finished.error)
        try:
            return self._finish(api.apply(finished.tasks, finished.outcome))
        except api.ComputeError as e:
            return self._finish(e)


    def cancel(self, context):
        """Blender ends the operator from outside (a file is loaded, the window closes): drop the run."""
        context.window_manager.event_timer_remove(self._timer)
        if job.current() is self._job:
            self._job.cancel()
            job.finish()


class CM_OT_cancel(bpy.types.Operator):
    """Stop the running computation; nothing is changed"""
    bl_idname = "consistent_maps.cancel"
    bl_label = "Cancel"

    @classmethod
    def poll(cls, context):
        return job.current() is not None

    def execute(self, context):
        job.current().cancel()
        return {'FINISHED'}


CLASSES = (CM_OT_compute, CM_OT_cancel)
