"""Scripting API: what the panel's operators do, for scripts and batch runs.

    from consistent_maps import api          # 4.2+ extension: from bl_ext.<repo>.consistent_maps import api
    api.add_feature(head, "nose", 1234)
    api.compute([head, other_head], effort=1) # same features land on the same sphere points
    sphere = api.sphere(head)                 # (n, 3) numpy array, row i = vertex i
    remeshes = api.remesh([head, other_head], 64)
    api.morph(head, other_head, align='features')   # shape key "→ Other" on head
    api.animate_morph(head, 1, 24)
    api.transfer(other_head, head, uv_maps=["UVMap"])
    api.bake_normal_map(other_head, head, 2048)      # other's normals in head's UV layout

compute() runs synchronously; the Compute operator runs the same three steps,
prepare (main thread), run (worker thread) and apply (main thread), without
blocking the interface. Objects are only modified once everything succeeded.
"""
import os
import re
import uuid
from dataclasses import dataclass, field

import numpy as np

from . import features as _features
from . import blends, connectivity, maps, meshdata, morphs, native, preview, results, topology
from . import pca as _pca


class ComputeError(ValueError):
    """The objects cannot be computed (or the result not stored); the message says what to fix."""


MapError = maps.MapError  # two objects without a common map, or a missing layer
RemeshSetError = connectivity.RemeshSetError  # objects that are no consistent remeshes of one connectivity
EXPLAINED_VARIANCE = _pca.VARIANCE  # custom property of pca()'s mean object
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
    feature_vertices: list  # vertex of each of the set's features in Outcome.feature_names order, -1: lacks it
    genus: int = 0


@dataclass
class Outcome:
    """What a run computed, for apply(): per task (sphere, stats, surface, refinement), surface being the
    (vertices, triangles, sphere) of the map and refinement (input triangle of each surface triangle,
    Steiner vertices, Steiner weights); and the feature locations common to the set. Two objects mapped
    onto each other (genus >= 1, or genus 0 as a pair): per task (None, stats, None, None) and pair_maps."""
    members: list
    feature_names: list
    feature_locations: list = field(default_factory=list)
    # Two objects mapped onto each other: per task (triangle (n,), weights (n, 3)) of its vertices on the other, then
    # (triangle (loops,), weights (loops, 3)) of its corners (loops), each from a point of its own face
    pair_maps: list = None


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


def prepare(objects, pair_map=False):
    """Validates the objects and copies their meshes out; raises ComputeError listing every problem.
    Two objects of genus >= 1, or of genus 0 with `pair_map`, are mapped onto each other (see run())."""
    objects = list(objects)
    found = _object_problems(objects)
    if found:
        raise ComputeError("\n".join(found))
    tasks, reports = [], []
    names = _features.shared_names(objects)
    for obj in objects:
        arrays = meshdata.extract(obj)
        reports.append(native.check_mesh(arrays.vertices, arrays.triangles))
        placed = _features.features(obj)
        tasks.append(Task(obj.name, arrays, [placed.get(name, -1) for name in names], reports[-1]["genus"]))
    found += topology.problems([obj.name for obj in objects], reports, pair_map)
    pair = topology.is_pair(reports, pair_map)
    found += _features.problems(objects, minimum=0 if pair else _features.MIN_SHARED)
    if found:
        raise ComputeError("\n".join(found))
    return tasks


def feature_names(objects):
    """The names of the features a computation of these objects puts into correspondence, in order."""
    return _features.shared_names(list(objects))


def run(tasks, names, *, effort=1, seed=1, threads=None, progress=None, restarts=1, align=False, pair_map=False):
    """The computation proper, touching no Blender data (safe in a worker thread); returns an Outcome.

    One object: its unconstrained map. Several: the consistent parameterization of the set, each
    feature of `names` landing on one common sphere point on every member that has it (a member
    lacking a feature, -1 in its Task, is left free there). Several objects are computed `restarts` times
    (seeds seed, seed + 1, ...), the best run kept; with `align` every member's map is then refitted
    towards the first complete member's where that lowers the distortion between them (poses of one
    shape slide less between the features; pairs of genus >= 1 ignore it). Two objects of genus >= 1, or
    of genus 0 with `pair_map`, are mapped onto each other by the inter-surface map instead (genus 0: through
    the sphere and directly through a consistent partition, the less distorted kept).
    progress(fraction of the whole run, text) returning False cancels: raises Cancelled.
    """
    threads = threads or os.cpu_count() or 1

    def forward(fraction, stage):
        return progress is None or progress(fraction, stage) is not False
    try:
        if len(tasks) == 2 and (tasks[0].genus >= 1 or pair_map):
            return _run_pair(tasks, names, effort=effort, seed=seed, threads=threads, progress=forward,
                             restarts=restarts)
        if len(tasks) == 1:
            arrays = tasks[0].arrays
            sphere_, stats = native.spherical_parameterization(
                arrays.vertices, arrays.triangles, effort=effort, seed=seed, threads=threads, progress=forward)
            vertices = tasks[0].feature_vertices
            unrefined = (np.arange(len(arrays.triangles)), np.empty((0, 3), int), np.empty((0, 3)))
            return Outcome([(sphere_, stats, (arrays.vertices, arrays.triangles, sphere_), unrefined)],
                           list(names), [sphere_[v] for v in vertices])
        result = native.consistent_spherical_parameterization(
            [(t.arrays.vertices, t.arrays.triangles) for t in tasks], [t.feature_vertices for t in tasks],
            effort=effort, seed=seed, threads=threads, progress=forward, restarts=restarts, align=align)
    except native.InvalidMeshError as e:  # the library numbers the members: name them
        raise ComputeError(re.sub(r"\bmesh (\d+)\b", lambda m: f"'{tasks[int(m.group(1))].name}'"
                                  if int(m.group(1)) < len(tasks) else m.group(0), str(e))) from e
    members = [(sphere_, dict(stats, set_seconds=result["seconds"]),
                (extras["refined_vertices"], extras["triangles"], extras["refined_sphere"]),
                (extras["input_triangle"], extras["steiner_vertices"], extras["steiner_weights"]))
               for sphere_, stats, extras in result["members"]]
    return Outcome(members, list(names), list(result["feature_locations"]))


def _run_pair(tasks, names, **options):
    """Two objects of equal genus: the inter-surface map (genus >= 1 through a consistent partition, Schreiner et
    al.; genus 0 that way and through the sphere, the less distorted kept)."""
    a, b = tasks
    pairs = [[i, j] for i, j in zip(a.feature_vertices, b.feature_vertices) if i >= 0 and j >= 0]
    try:
        r = native.intersurface_map((a.arrays.vertices, a.arrays.triangles), (b.arrays.vertices, b.arrays.triangles),
                                    np.array(pairs, dtype=np.int64).reshape(-1, 2), corner_images=True, **options)
    except native.InvalidMeshError as e:  # the library calls them A and B
        raise ComputeError(re.sub(r"\b([AB])\b(?=:| has| \()", lambda m: f"'{tasks['AB'.index(m.group(1))].name}'",
                                  str(e))) from e
    # The median says how distorted most of the surface is; a few near-degenerate triangles rule the mean.
    # Folded samples are the vertex sampling's; the map's own folds (map_flipped) say whether it is bijective.
    stats = [{"genus": r["genus"], "method": r["method"], "symmetric_dirichlet": float(d),
              "median_symmetric_dirichlet": float(m), "folded_samples": int(f), "seconds": r["seconds"],
              "bijective": r["map_flipped"] == 0}
             for d, m, f in zip(r["symmetric_dirichlet"], r["median_symmetric_dirichlet"], r["flipped"])]
    pair_maps = []
    for task, (this, other) in zip(tasks, ("ab", "ba")):
        loops = meshdata.loop_corners(task.arrays.corners)  # native corner 3 t + k is loop corners[t, k]
        pair_maps.append((r[f"{this}_to_{other}_triangle"], r[f"{this}_to_{other}_barycentric"],
                          r[f"{this}_corners_to_{other}_triangle"][loops],
                          r[f"{this}_corners_to_{other}_barycentric"][loops]))
    return Outcome([(None, s, None, None) for s in stats], list(names), pair_maps=pair_maps)


def apply(tasks, outcome):
    """Stores the outcome on the objects and the scene, if no object changed meanwhile; returns {name: stats}."""
    import bpy
    objects = [bpy.data.objects.get(task.name) for task in tasks]
    changed = [task.name for task, obj in zip(tasks, objects)
               if obj is None or obj.type != 'MESH' or obj.mode == 'EDIT'
               or meshdata.fingerprint(obj.data) != task.arrays.fingerprint]
    if changed:
        raise ComputeError(f"{', '.join(repr(n) for n in changed)} changed during the computation: "
                           f"nothing was stored, press Compute again")
    token = uuid.uuid4().hex
    for i, (task, obj, (sphere_, stats, surface, refinement)) in enumerate(zip(tasks, objects, outcome.members)):
        if outcome.pair_maps:
            preview.hide(obj)
            results.store_pair(obj.data, *outcome.pair_maps[i], task.arrays.fingerprint, stats, token)
            continue
        results.store(obj.data, sphere_, task.arrays.fingerprint, stats, surface, refinement, token)
        if preview.is_shown(obj):
            preview.show(obj)
    results.store_set(bpy.context.scene, token, outcome.feature_names, outcome.feature_locations)
    return {task.name: member[1] for task, member in zip(tasks, outcome.members)}


def compute(objects, *, effort=1, seed=1, threads=None, progress=None, restarts=1, align=False, pair_map=False):
    """Maps every object onto the sphere and stores the results; returns {object name: stats}.

    With several objects the maps are consistent: each feature lands on the same sphere point on every
    object that has it. An object may lack features (no CM: group), but every feature must be on at least
    two objects, every object needs at least 3 of them, and one object all (feature_problems() says what
    is missing); api.remesh() then builds consistent remeshes. `restarts` > 1 computes several objects
    that many times (other seeds) and keeps the best run: with few features one run can twist an object's
    map around them. `align` refits every object's map towards the first complete object's (see run()).
    `pair_map`: two objects of genus 0 are mapped onto each other directly, like pairs of genus >= 1 (see
    run()): no sphere preview then.

    Raises ComputeError (invalid input, nothing modified) or Cancelled (progress returned False).
    """
    objects = list(objects)
    tasks = prepare(objects, pair_map=pair_map)
    return apply(tasks, run(tasks, feature_names(objects), effort=effort, seed=seed, threads=threads,
                            progress=progress, restarts=restarts, align=align, pair_map=pair_map))


def _mapped_directly(obj):
    return obj.type == 'MESH' and result_state(obj) == results.CURRENT and results.pair_map(obj.data) is not None


def _remesh_problems(objects, resolution, scene):
    if not objects:
        return ["The set is empty: select mesh objects and press Add Selected"]
    found = [] if resolution >= 2 and resolution % 2 == 0 else [
        f"The remesh resolution must be even and at least 2, not {resolution}"]
    paired = [obj for obj in objects if _mapped_directly(obj)]
    if paired:
        if len(objects) != 2 or len(paired) != 2:
            return found + [f"'{obj.name}' is mapped directly onto its partner: remesh the set of those two objects "
                            f"alone" for obj in paired]
        return found + maps.problems(objects)
    for obj in objects:
        state = result_state(obj) if obj.type == 'MESH' else results.NONE
        if state != results.CURRENT or results.surface(obj.data) is None:
            found.append(f"'{obj.name}' has no {'current ' if state == results.STALE else ''}result: press Compute")
        elif results.set_token(obj.data) != results.set_token(scene):
            found.append(f"'{obj.name}' was not computed with the set last computed here: press Compute")
    return found


def _pair_remesh(a, b, resolution):
    """(native remesh_pair result with 'positions', feature names) of a pair mapped directly."""
    on_a, on_b = _features.features(a), _features.features(b)
    shared = [name for name in on_a if name in on_b]
    to_b, to_a = maps.vertex_landing(a, b), maps.vertex_landing(b, a)
    pairs = np.array([[on_a[name], on_b[name]] for name in shared], dtype=np.int64).reshape(-1, 2)
    remeshed = native.remesh_pair(meshdata.arrays(a.data), meshdata.arrays(b.data), (to_b.triangle, to_b.barycentric),
                                  (to_a.triangle, to_a.barycentric), pairs, resolution * resolution + 2)
    remeshed["positions"] = [remeshed["a_positions"], remeshed["b_positions"]]
    return remeshed, shared


def remesh(objects, resolution=64, *, threads=None):
    """Consistent remeshes of computed objects: new objects sharing one connectivity, each feature at the
    same vertex index on all, in the collection "Consistent Maps". The objects are not modified. A set
    through the sphere is sampled on its octahedral grid of even `resolution` (resolution^2 + 2 vertices);
    a pair mapped directly (genus >= 1, or Map the Pair Directly) is simplified to that many vertices, or as
    far as it goes without folding a triangle: one object's own vertices, and their images on the other
    (whichever way folds less). Returns the new objects."""
    import bpy

    from . import remeshes  # Blender-only, like everything that creates data
    objects, scene = list(objects), bpy.context.scene
    found = _remesh_problems(objects, resolution, scene)
    if found:
        raise ComputeError("\n".join(found))
    if _mapped_directly(objects[0]):
        remeshed, names = _pair_remesh(*objects, resolution)
        pair = {"carrier": objects[1 if remeshed["b_carries"] else 0].name,
                "folded_triangles": int(remeshed["folded_triangles"])}
        return remeshes.create(scene, objects, remeshed, names, pair)
    locations = results.feature_locations(scene)
    remeshed = native.consistent_remesh(
        [results.surface(obj.data) for obj in objects], np.array(list(locations.values()), dtype=float).reshape(-1, 3),
        resolution, threads=threads or os.cpu_count() or 1)
    return remeshes.create(scene, objects, remeshed, list(locations))


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


def morph(source, target, align='features'):
    """Adds (or refreshes) the shape key "→ <target name>" on source: each source vertex where the
    common map puts it on target, so source takes target's shape with its own mesh, UVs and materials.
    align: 'none' (target's coordinates as they are), 'bounds' (target's bounding box onto source's,
    scaled by the diagonals) or 'features' (the least-squares similarity taking target's features onto
    source's). Both objects need current results of one computed set; raises MapError otherwise (nothing
    is modified). Returns the shape key."""
    return morphs.add(source, target, align)


def animate_morph(obj, frame_start, frame_end, ping_pong=False, key=None):
    """Keyframes the value of obj's morph key (by default the last one made; key: its name) from 0 at
    frame_start to 1 at frame_end, or 0 → 1 → 0 with ping_pong. Returns the shape key."""
    return morphs.animate(obj, frame_start, frame_end, ping_pong, key)


def transfer(source, target, uv_maps=(), color_attributes=(), normals=False, vertex_groups=(), attributes=()):
    """Copies layers of source onto target through the common map: UV maps (per corner, seams kept),
    colour attributes (point or corner, byte or float), custom split normals, vertex groups and float
    attributes (point or corner), by name; target layers of the same names are overwritten. Raises
    MapError (nothing modified) when the objects have no common map or source lacks a layer. Returns
    what was transferred."""
    from . import transfer as _transfer  # Blender-only
    return _transfer.transfer(source, target, uv_maps, color_attributes, normals, vertex_groups, attributes)


def show_distortion(obj, other):
    """Colours obj by how the common map onto other distorts it, so features can be added where it stretches:
    the face-corner colour attribute "Map distortion" (replaced if there), made the active colour: white at the
    symmetric Dirichlet energy's optimum 4, yellow at 16, red from 64 on, magenta where a face's image folds.
    Raises MapError (nothing modified) when the two have no common map. Returns the map's summary onto other:
    'median' and 'mean' (area-weighted) energy, 'folded' triangles and 'high_area', the share of obj's area at
    16 or more."""
    from . import distortion  # Blender-only
    return distortion.show(obj, other)


def pca(objects, k=3):
    """The mean shape of consistent remeshes (one connectivity) as a new object "Mean shape" in the
    collection "Consistent Maps", with a shape key per principal component (the first k) at +3 standard
    deviations (slider -1 to 1 for -3 to +3 sd), named with the share of variance it explains; the shares
    are also its custom property cm_explained_variance. Raises RemeshSetError (nothing created)."""
    return _pca.create(objects, k)


def blend(objects):
    """An n-way blend of consistent remeshes: the new object "Blend" (collection "Consistent Maps") with the
    first remesh as its basis and a shape key "→ <name>" per other remesh. Raises RemeshSetError."""
    return blends.create(objects)


def bake_texture(source, target, image_size=1024, margin=16, progress=None):
    """Texture transfer: a new image (image_size²) holding source's image texture (the first in its
    materials, at the UV map its node uses) in target's active UV layout, through the common map; Cycles
    bakes it, padding `margin` pixels beyond the seams. Target and source are not modified. Raises
    MapError (nothing created) when they have no common map, source has no image texture or target no
    UV map. Returns the image (not saved: pack or save it). progress(fraction), if given, is called as the
    steps finish (Blender is busy meanwhile: the operator shows it as the progress indicator)."""
    from . import bake  # Blender-only
    return bake.bake(source, target, image_size, margin, progress)


def bake_normal_map(source, target, image_size=1024, margin=16, align='features', progress=None):
    """Normal-map transfer: a new image (image_size², Non-Color) holding source's shading normals (smooth,
    flat or custom) as a tangent-space normal map in target's active UV layout, through the common map, so
    that target rendered with it (Image Texture at that UV map, Non-Color, into a Normal Map node in
    tangent space) shows source's normals; Blender's tangent space (MikkTSpace) is used, as Cycles bakes
    it. align: 'features' turns source's normals by the least-squares rotation taking its features onto
    target's (needs 3 shared features), 'none' takes them as they are (object space). Target and source
    are not modified. Raises MapError (nothing created) when they have no common map, target has no UV
    map or align cannot be done. Returns the image (not saved: pack or save it). progress(fraction), if
    given, is called as the steps finish."""
    from . import bake  # Blender-only
    return bake.bake_normals(source, target, image_size, margin, align, progress)

