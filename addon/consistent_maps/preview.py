"""Sphere preview: a shape key that wraps the object onto its computed sphere.

The sphere is centred on the object's bounding box and scaled to its size, so
the preview sits where the object is. Hiding the preview removes the key (and the
Basis key too when the preview created it), leaving the mesh as it was.
"""
import numpy as np

from . import meshdata, results

KEY = "CM Sphere"
CREATED_BASIS = "cm_preview_created_basis"


class PreviewError(ValueError):
    """No preview can be shown; the message says why."""


def is_shown(obj):
    keys = obj.data.shape_keys
    return keys is not None and KEY in keys.key_blocks


def _positions(mesh, sphere):
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float64)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    low, high = co.min(axis=0), co.max(axis=0)
    return (low + high) / 2 + sphere * (high - low).max() / 2


def problem(obj):
    """Why the preview of obj cannot be shown, or None."""
    state = results.state(obj.data, meshdata.fingerprint(obj.data))
    if state == results.NONE:
        return f"'{obj.name}' has no result yet: press Compute first"
    if state == results.STALE:
        return f"The result of '{obj.name}' is stale (the mesh changed): press Compute again"
    if obj.mode == 'EDIT':
        return f"'{obj.name}' is in Edit Mode: leave it to show the sphere"
    if results.pair_map(obj.data) is not None:
        return f"'{obj.name}' is mapped directly onto its partner: it has no sphere to show"
    return None


def show(obj):
    """Adds or refreshes the preview key from the stored result and sets it to full strength."""
    reason = problem(obj)
    if reason:
        raise PreviewError(reason)
    mesh = obj.data
    sphere = results.sphere(mesh)
    if mesh.shape_keys is None:
        obj.shape_key_add(name="Basis", from_mix=False)
        mesh[CREATED_BASIS] = True
    key = mesh.shape_keys.key_blocks.get(KEY) or obj.shape_key_add(name=KEY, from_mix=False)
    key.data.foreach_set("co", _positions(mesh, sphere).astype(np.float32).ravel())
    key.value = 1.0
    obj.active_shape_key_index = 0  # edits keep going to the basis, not to the sphere
    mesh.update()


def hide(obj):
    """Removes the preview key; a no-op when it is not shown."""
    if not is_shown(obj):
        return
    mesh = obj.data
    obj.shape_key_remove(mesh.shape_keys.key_blocks[KEY])
    if mesh.get(CREATED_BASIS) and len(mesh.shape_keys.key_blocks) == 1:
        obj.shape_key_remove(mesh.shape_keys.key_blocks[0])
    mesh.pop(CREATED_BASIS, None)
    mesh.update()
