"""Computed results, stored on the mesh so they persist in the .blend.

The sphere coordinates are a FLOAT_VECTOR point attribute; next to them, as
custom properties of the mesh, the fingerprint of the mesh they were computed
from (an edited mesh no longer matches: the result is stale) and the numbers of
the computation.
"""
import numpy as np

ATTRIBUTE = "cm_sphere"
FINGERPRINT = "cm_fingerprint"
STATS = "cm_stats"

NONE, CURRENT, STALE = "NONE", "CURRENT", "STALE"


def store(mesh, sphere, fingerprint, stats):
    old = mesh.attributes.get(ATTRIBUTE)
    if old is not None:
        mesh.attributes.remove(old)
    attribute = mesh.attributes.new(ATTRIBUTE, 'FLOAT_VECTOR', 'POINT')
    attribute.data.foreach_set("vector", np.ascontiguousarray(sphere, dtype=np.float32).ravel())
    mesh[FINGERPRINT] = fingerprint
    mesh[STATS] = {k: v for k, v in stats.items() if isinstance(v, (bool, int, float, str))}


def sphere(mesh):
    """(n, 3) float32 sphere coordinates, or None if the mesh has no result."""
    attribute = mesh.attributes.get(ATTRIBUTE)
    if attribute is None or attribute.domain != 'POINT' or attribute.data_type != 'FLOAT_VECTOR':
        return None
    values = np.empty(len(attribute.data) * 3, dtype=np.float32)
    attribute.data.foreach_get("vector", values)
    return values.reshape(-1, 3)


def stats(mesh):
    return dict(mesh[STATS]) if STATS in mesh else {}


def state(mesh, current_fingerprint):
    """NONE (never computed), CURRENT, or STALE (the mesh changed since)."""
    if mesh.attributes.get(ATTRIBUTE) is None or FINGERPRINT not in mesh:
        return NONE
    return CURRENT if mesh[FINGERPRINT] == current_fingerprint else STALE
