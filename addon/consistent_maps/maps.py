"""The maps between computed objects, read from their stored results, and why a pair has none."""
import numpy as np

from . import mapping, meshdata, results


class MapError(ValueError):
    """Two objects cannot be mapped onto each other (or a layer is missing); the message says what to fix."""


def _object_problem(obj):
    if obj is None or obj.type != 'MESH':
        return f"'{getattr(obj, 'name', obj)}' is not a mesh object"
    if obj.mode == 'EDIT':
        return f"'{obj.name}' is in Edit Mode: leave Edit Mode first"
    state = results.state(obj.data, meshdata.fingerprint(obj.data))
    if state == results.STALE:
        return f"The result of '{obj.name}' is stale (the mesh changed): press Compute again"
    if state == results.NONE:
        return f"'{obj.name}' has no result: add it to the set and press Compute"
    if results.refinement(obj.data) is None and results.pair_map(obj.data) is None:
        return f"The result of '{obj.name}' predates maps between objects: press Compute again"
    if results.pair_map(obj.data) is not None and results.pair_corner_map(obj.data) is None:
        return f"The result of '{obj.name}' predates per-corner maps between objects: press Compute again"
    return None


def problems(objects):
    """Why the objects cannot be mapped onto each other (empty when they can): each must have a current
    result, all from one computation of a set."""
    found = [p for p in map(_object_problem, objects) if p]
    if found:
        return found
    if len({obj.name for obj in objects}) < len(objects):
        return ["An object cannot be mapped onto itself: choose two different objects"]
    if len({results.set_token(obj.data) for obj in objects}) > 1:
        names = " and ".join(f"'{obj.name}'" for obj in objects)
        return [f"{names} were not computed together: put them in one set and press Compute"]
    return []


def check(objects):
    """Raises MapError listing every problem of problems(objects)."""
    found = problems(objects)
    if found:
        raise MapError("\n".join(found))


def parameterization(obj):
    """The stored map of a checked object as a mapping.Parameterization."""
    _, refined_triangles, refined_sphere = results.surface(obj.data)
    input_triangle, input_vertices, input_weights = results.refinement(obj.data)
    return mapping.Parameterization(refined_sphere, refined_triangles, input_triangle, input_vertices,
                                    input_weights, meshdata.loop_triangles(obj.data)[0])


def positions(mesh):
    co = np.empty(len(mesh.vertices) * 3, dtype=np.float64)
    mesh.vertices.foreach_get("co", co)
    return co.reshape(-1, 3)


def vertex_landing(source, target):
    """Where each vertex of source lands on target (checked objects)."""
    pair = results.pair_map(source.data)
    if pair is not None:
        return mapping.Landing(*pair)
    return mapping.land(parameterization(target), results.sphere(source.data).astype(np.float64))


def corner_landing(source, target):
    """Where each corner (loop) of target lands on source: from the target corner's own triangle, so
    per-corner source values are taken from the matching side of a seam. Objects mapped directly onto
    each other (genus >= 1, or genus 0 as a pair) store these images per corner."""
    pair = results.pair_corner_map(target.data)
    if pair is not None:
        return mapping.Landing(*pair)
    target_map = parameterization(target)
    first = meshdata.loop_corners(meshdata.loop_triangles(target.data)[1])
    directions = mapping.corner_directions(target_map).reshape(-1, 3)[first]
    return mapping.land(parameterization(source), directions)


def first_corners(mesh):
    """Per corner (loop) of the mesh: the first corner of its face."""
    starts = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_start", starts)
    sizes = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", sizes)
    loops = np.repeat(starts, sizes) + np.arange(sizes.sum()) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    first = np.empty(len(mesh.loops), dtype=np.int64)
    first[loops] = np.repeat(starts, sizes)
    return first


def uvs_at_corners(source, target, landing, uv):
    """Source's texture coordinates uv (one row per source corner) at target's corners (landing: where they
    land, corner_landing(source, target)), each target face's corners in one chart of source's layout: a face
    whose image straddles a seam of source's UV map gets coordinates continuing across it."""
    triangles, corners = meshdata.loop_triangles(source.data)
    return mapping.at_corners_in_face_charts(landing, triangles, corners, uv, first_corners(target.data))
