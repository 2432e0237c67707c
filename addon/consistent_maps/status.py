"""What the panel shows about one object: its topology, features and result.

The topology report comes from the native mesh check and is cached by mesh
fingerprint, so redrawing the panel re-checks a mesh only after it changed.
In Edit Mode the mesh as of entering Edit Mode is described.
"""
from dataclasses import dataclass, field

from . import features, meshdata, native, results

_reports = {}
_CACHE_SIZE = 64


@dataclass
class Status:
    triangles: int
    genus: int
    manifold: bool
    report: dict  # native.check_mesh's (topology.problems reads it)
    placed: list = field(default_factory=list)      # feature names with one vertex
    unplaced: list = field(default_factory=list)    # names with no vertex yet
    ambiguous: list = field(default_factory=list)   # names with several vertices
    result: str = results.NONE


def _report(mesh):
    key = meshdata.fingerprint(mesh)
    if key not in _reports:
        if len(_reports) >= _CACHE_SIZE:
            _reports.clear()
        _reports[key] = native.check_mesh(*meshdata.arrays(mesh))
    return key, _reports[key]


def of(obj):
    key, report = _report(obj.data)
    members = features.memberships(obj)
    return Status(
        triangles=report["faces"],
        genus=report["genus"],
        manifold=report["manifold"],
        report=report,
        placed=[n for n, v in members.items() if len(v) == 1],
        unplaced=[n for n, v in members.items() if not v],
        ambiguous=[n for n, v in members.items() if len(v) > 1],
        result=results.state(obj.data, key),
    )
