"""Scripting API: what the panel's operators do, for scripts and batch runs.

    from consistent_maps import api          # 4.2+ extension: from bl_ext.<repo>.consistent_maps import api
    api.add_feature(head, "nose", 1234)
    api.compute([head, other_head], effort=1)
    sphere = api.sphere(head)                 # (n, 3) numpy array, row i = vertex i

compute() runs synchronously; the Compute operator runs the same three steps,
prepare (main thread), run (worker thread) and apply (main thread), without
blocking the interface. Objects are only modified once everything succeeded.
"""
import os
from dataclasses import dataclass

from . import features as _features
from . import meshdata, native, preview, results

class ComputeError(ValueError):
    """The objects cannot be computed (or the result not stored); the message says what to fix."""


FeatureError = _features.FeatureError
PreviewError = preview.PreviewError
Cancelled = native.Cancelled


def add_feature(obj, name, vertex_index):
    """Places feature `name` (vertex group CM:<name>) at vertex_index of obj; returns the cleaned name."""
    return _features.add(obj, name, vertex_index)


def features(obj):
    """{name: vertex index} of the features placed on obj."""
    return _features.features(obj)


def rename_feature(objects, old, new):
    return _features.rename(objects, old, new)


def delete_feature(objects, name):
    return _features.delete(objects, name)


def copy_feature_names(source, targets):
    """Gives the targets (unplaced) features of the names the source has; returns how many were added."""
    return _features.copy_names(source, targets)


def feature_problems(objects):
    return _features.problems(objects)


@dataclass
class Task:
    """One object's input, copied out so the computation needs no Blender data."""
    name: str
    arrays: meshdata.MeshArrays


def _object_problems(objects):
    if not objects:
        return ["The set is empty: select mesh objects and press Add Selected"]
    found = []
    seen = set()
    for obj in objects:
        if obj.type != 'MESH':
            found.append(f"'{obj.name}' is not a mesh object")
        elif obj.mode == 'EDIT':
            found.append(f"'{obj.name}' is in Edit Mode: leave Edit Mode first")
        if obj.name in seen:
            found.append(f"'{obj.name}' is in the set more than once")
        seen.add(obj.name)
    return found


def _mesh_problem(name, report):
    hint = ""
    if not report["manifold"]:
        hint = " (Select > Select All by Trait > Non Manifold shows where)"
    return f"'{name}': {report['sphere_error']}{hint}"


def prepare(objects):
    """Validates the objects and copies their meshes out; raises ComputeError listing every problem."""
    objects = list(objects)
    found = _object_problems(objects)
    if found:
        raise ComputeError("\n".join(found))
    tasks = []
    for obj in objects:
        arrays = meshdata.extract(obj)
        report = native.check_mesh(arrays.vertices, arrays.triangles)
        if report["sphere_error"]:
            found.append(_mesh_problem(obj.name, report))
        tasks.append(Task(obj.name, arrays))
    found += _features.problems(objects)
    if found:
        raise ComputeError("\n".join(found))
    return tasks


def run(tasks, *, effort=1, seed=1, threads=None, progress=None):
    """The computation proper, touching no Blender data (safe in a worker thread).

    progress(fraction of the whole run, text) returning False cancels: raises Cancelled.
    Returns one (sphere, stats) per task.
    """
    threads = threads or os.cpu_count() or 1
    outputs = []
    for i, task in enumerate(tasks):
        def forward(fraction, stage, i=i, name=task.name):
            return progress is None or progress((i + fraction) / len(tasks), f"{name}: {stage}") is not False
        try:
            outputs.append(native.spherical_parameterization(
                task.arrays.vertices, task.arrays.triangles,
                effort=effort, seed=seed, threads=threads, progress=forward))
        except native.InvalidMeshError as e:
            raise ComputeError(f"'{task.name}': {e}") from e
    return outputs


def apply(tasks, outputs):
    """Stores the outputs on the objects, if none of them changed meanwhile; returns {name: stats}."""
    import bpy
    objects = [bpy.data.objects.get(task.name) for task in tasks]
    changed = [task.name for task, obj in zip(tasks, objects)
               if obj is None or obj.type != 'MESH' or obj.mode == 'EDIT'
               or meshdata.fingerprint(obj.data) != task.arrays.fingerprint]
    if changed:
        raise ComputeError(f"{', '.join(repr(n) for n in changed)} changed during the computation: "
                           f"nothing was stored, press Compute again")
    for task, obj, (sphere_, stats) in zip(tasks, objects, outputs):
        results.store(obj.data, sphere_, task.arrays.fingerprint, stats)
        if preview.is_shown(obj):
            preview.show(obj)
    return {task.name: stats for task, (_, stats) in zip(tasks, outputs)}


def compute(objects, *, effort=1, seed=1, threads=None, progress=None):
    """Maps every object onto the sphere and stores the results; returns {object name: stats}.

    Raises ComputeError (invalid input, nothing modified) or Cancelled (progress returned False).
    """
    tasks = prepare(objects)
    return apply(tasks, run(tasks, effort=effort, seed=seed, threads=threads, progress=progress))


def sphere(obj):
    """The stored sphere coordinates of obj ((n, 3) numpy array), or None if missing or stale."""
    if results.state(obj.data, meshdata.fingerprint(obj.data)) != results.CURRENT:
        return None
    return results.sphere(obj.data)


def result_state(obj):
    """'NONE', 'CURRENT' or 'STALE' (the mesh was edited after computing)."""
    return results.state(obj.data, meshdata.fingerprint(obj.data))


def show_sphere(obj, shown=True):
    """Shows (shape key 'CM Sphere' at full strength) or hides the sphere preview of obj."""
    if shown:
        preview.show(obj)
    else:
        preview.hide(obj)
