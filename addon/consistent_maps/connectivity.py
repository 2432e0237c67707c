"""Objects sharing one connectivity (consistent remeshes): vertex i of each is the same point of the set."""
import numpy as np


class RemeshSetError(ValueError):
    """The objects are no consistent remeshes of one connectivity (or the request does not fit them)."""


def _loops(mesh):
    loops = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", loops)
    return loops


def check(objects, purpose):
    """Raises RemeshSetError unless objects are at least 2 meshes with the first one's connectivity;
    purpose ("Principal components", ...) starts the message."""
    if any(obj.type != 'MESH' for obj in objects):
        raise RemeshSetError(f"{purpose} need mesh objects (consistent remeshes) only")
    if len(objects) < 2:
        raise RemeshSetError(f"{purpose} need at least 2 consistent remeshes, got {len(objects)}")
    first = _loops(objects[0].data)
    found = [f"'{obj.name}' does not share the connectivity of '{objects[0].name}': use consistent remeshes "
             f"of one computation (Remesh)" for obj in objects[1:]
             if len(obj.data.vertices) != len(objects[0].data.vertices) or not np.array_equal(_loops(obj.data), first)]
    if found:
        raise RemeshSetError("\n".join(found))
