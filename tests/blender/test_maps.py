"""Maps between computed objects in real Blender: mapping primitives, morphs and their animation,
attribute transfer (accuracy on a set with known correspondence), error paths, a rendered morph.

Run by run_tests.py after test_addon.py, whose helpers it uses.
"""
import time

import bpy
import numpy as np

from consistent_maps import api, mapping, maps, meshdata
from test_addon import BALL, OUT, ROOT, SHARED, VERSION, expect_error, load, make_set, select, snapshot, with_features

CACTUS = SHARED / "sets" / "cactus"


def _pair():
    """Two balls of different shapes with the same features, computed as one set (fast)."""
    a = with_features(load(BALL, "A"))
    b = load(BALL, "B", location=(3, 0, 0))
    b.data.transform(np.diag([1.0, 1.6, 0.8, 1.0]))
    with_features(b)
    make_set([a, b])
    api.compute([a, b], effort=0)
    return a, b


def _farthest(vertices, count):
    chosen = [0]
    distance = np.full(len(vertices), np.inf)
    while len(chosen) < count:
        distance = np.minimum(distance, ((vertices - vertices[chosen[-1]]) ** 2).sum(axis=1))
        chosen.append(int(distance.argmax()))
    return chosen


def _get(collection, field, width, dtype=np.float32):
    values = np.empty(len(collection) * width, dtype=dtype)
    collection.foreach_get(field, values)
    return values.reshape(-1, width) if width > 1 else values


def _cylinder_uv(mesh, axis=2):
    """Per-corner UVs around the coordinate axis `axis` (default vertical; triangles only): u the angle, v
    along the axis, with a seam: the corners of a face across it get u + 1, so the same vertex has two UVs
    there."""
    x, y = (i for i in range(3) if i != axis)
    co = maps.positions(mesh)
    centre = (co.min(axis=0) + co.max(axis=0)) / 2
    loops = _get(mesh.loops, "vertex_index", 1, np.int32)
    u = (np.arctan2(co[:, y] - centre[y], co[:, x] - centre[x]) / (2 * np.pi) + 0.5)[loops].reshape(-1, 3)
    wraps = (u.max(axis=1) - u.min(axis=1) > 0.5)[:, None] & (u < 0.5)
    u = np.where(wraps, u + 1, u)
    return np.column_stack([u.ravel(), co[loops, axis]])


def _new_uv(mesh, name, uv):
    mesh.uv_layers.new(name=name).data.foreach_set("uv", uv.astype(np.float32).ravel())


def _colours(co):
    rgb = (co - co.min(axis=0)) / (co.max(axis=0) - co.min(axis=0))
    return np.hstack([rgb, np.ones((len(rgb), 1))]).astype(np.float32)


# -- mapping primitives ---------------------------------------------------------------------------

def test_vertex_landing_is_a_convex_combination_on_the_target():
    a, b = _pair()
    landing = maps.vertex_landing(a, b)
    triangles, _ = meshdata.loop_triangles(b.data)
    assert landing.triangle.shape == (len(a.data.vertices),)
    assert landing.triangle.min() >= 0 and landing.triangle.max() < len(triangles)
    assert (landing.barycentric >= 0).all() and np.allclose(landing.barycentric.sum(axis=1), 1)
    # features land on the features (same sphere point): the mapped feature is the target's feature vertex
    mapped = mapping.at_vertices(landing, triangles, maps.positions(b.data))
    for name, vertex in api.features(a).items():
        assert np.allclose(mapped[vertex], b.data.vertices[api.features(b)[name]].co, atol=1e-4), name


def test_corner_landing_covers_every_corner():
    a, b = _pair()
    landing = maps.corner_landing(a, b)
    assert landing.triangle.shape == (len(b.data.loops),)
    assert np.allclose(landing.barycentric.sum(axis=1), 1)


# -- accuracy on a set with known correspondence (vertex i <-> vertex i) ------------------------------

def _relative_errors(source, target):
    """Positions, a point colour and a seamed UV map of source brought onto target through the maps,
    against target's own values: mean error / value range, each."""
    target_co = maps.positions(target.data)
    start = time.perf_counter()
    key = api.morph(source, target, align='none')
    print(f"  morph of {len(target_co)} vertices: {time.perf_counter() - start:.2f} s")
    morphed = _get(key.data, "co", 3)
    diagonal = np.linalg.norm(target_co.max(axis=0) - target_co.min(axis=0))
    position = np.linalg.norm(morphed - target_co, axis=1).mean() / diagonal

    truth_rgba = _colours(maps.positions(source.data))
    source.data.attributes.new("where", 'FLOAT_COLOR', 'POINT').data.foreach_set("color", truth_rgba.ravel())
    truth_uv = _cylinder_uv(source.data)  # the same per corner on target: shared connectivity
    _new_uv(source.data, "cylinder", truth_uv)
    api.transfer(source, target, uv_maps=["cylinder"], color_attributes=["where"])
    rgba = _get(target.data.color_attributes["where"].data, "color", 4)
    colour = np.abs(rgba[:, :3] - truth_rgba[:, :3]).mean()  # channels span [0, 1]
    uv = _get(target.data.uv_layers["cylinder"].data, "uv", 2)
    uv_range = truth_uv.max(axis=0) - truth_uv.min(axis=0)
    uv_error = (np.abs(uv - truth_uv) / uv_range).mean(axis=0).max()
    # Faces across the whole texture, beyond those near the axis that do so in the truth: seams lost.
    span = lambda u: (np.ptp(u[:, 0].reshape(-1, 3), axis=1) > 0.5).mean()  # noqa: E731 (triangles only)
    print(f"  {100 * (span(uv) - span(truth_uv)):.2f} % of the faces span the texture (beyond the truth's)")
    assert span(uv) - span(truth_uv) < 0.002, "a face whose image straddles a seam continues across it"
    return position, colour, uv_error


def _cactus_pair(other):
    source, target = load(CACTUS / "cactus0.ply", "Cactus 0"), load(CACTUS / f"{other}.ply", "Cactus other")
    for index, vertex in enumerate(_farthest(maps.positions(source.data), 10)):
        api.add_feature(source, f"f{index}", vertex)
        api.add_feature(target, f"f{index}", vertex)
    return source, target


def test_cactus_transfer_reproduces_the_targets_own_values():
    """Cactus poses share vertex order: through maps computed from 10 features, positions, a point colour
    and a UV map with a seam carried from one pose to another match the other's own (mean errors printed).
    The error is the maps' (stretch-minimizing maps of two poses are not vertex i <-> i; effort 0 doubles
    it), not the transfer's: test_transfer_between_identical_members_is_exact."""
    source, target = _cactus_pair("cactus3")
    api.compute([source, target], effort=2)
    position, colour, uv = _relative_errors(source, target)
    print(f"  cactus0 -> cactus3 mean error: positions {100 * position:.2f} % of the diagonal, "
          f"colour {100 * colour:.2f} %, UV {100 * uv:.2f} % of the range")
    assert position < 0.03 and colour < 0.05 and uv < 0.06, (position, colour, uv)


def test_transfer_between_identical_members_is_exact():
    """Two copies of one mesh get one map: positions, colours and the seamed UV map come out unchanged."""
    source, target = _cactus_pair("cactus0")
    api.compute([source, target], effort=0)
    position, colour, uv = _relative_errors(source, target)
    print(f"  cactus0 -> copy mean error: positions {100 * position:.4f} %, colour {100 * colour:.4f} %, "
          f"UV {100 * uv:.4f} %")
    assert position < 1e-3 and colour < 1e-3 and uv < 1e-3, (position, colour, uv)


# -- morphs -------------------------------------------------------------------------------------------

def test_morph_operator_adds_the_key_in_the_targets_shape():
    a, b = _pair()
    bpy.context.scene.consistent_maps.morph_target = b
    select([a])
    before = snapshot(b)
    for align in ('features', 'bounds', 'none'):
        bpy.context.scene.consistent_maps.morph_align = align
        assert bpy.ops.consistent_maps.morph() == {'FINISHED'}
        keys = a.data.shape_keys.key_blocks
        assert [k.name for k in keys] == ["Basis", "→ B"], "one key, refreshed"
        co = _get(keys["→ B"].data, "co", 3)
        assert co.shape == (len(a.data.vertices), 3) and np.isfinite(co).all()
        extent = co.max(axis=0) - co.min(axis=0)
        # B is A stretched by (1, 1.6, 0.8): the morph has B's proportions, A's size unless 'none'
        assert np.allclose(extent / extent[0], [1, 1.6, 0.8], atol=0.05), (align, extent)
    assert keys["→ B"].value == 0.0, "the morph starts off"
    assert snapshot(b) == before, "the target is not modified"
    assert api.sphere(a) is not None, "shape keys leave the result current"


def test_morph_aligned_by_features_undoes_a_rotation():
    """A target turned by 90 degrees and twice as large: aligned by features, the morph has the target's
    proportions in the source's frame, at the source's scale; 'none' keeps the turn (x and y swapped) and
    the size."""
    a, b = _pair()
    b.data.transform(np.array([[0, -1, 0, 0], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]) @ np.diag([2, 2, 2, 1.0]))
    api.compute([a, b], effort=0)
    extents = {}
    for align, proportions in (('features', [1, 1.6, 0.8]), ('none', [1, 0.625, 0.5])):
        extents[align] = np.ptp(_get(api.morph(a, b, align=align).data, "co", 3), axis=0)
        assert np.allclose(extents[align] / extents[align][0], proportions, atol=0.1), (align, extents[align])
    assert extents['none'].max() > 1.8 * extents['features'].max(), extents


def test_animate_morph_keyframes_the_value():
    a, b = _pair()
    key = api.morph(a, b)
    scene = bpy.context.scene
    settings = scene.consistent_maps
    settings.frame_start, settings.frame_end = 1, 24
    select([a])
    assert bpy.ops.consistent_maps.animate_morph() == {'FINISHED'}
    curve = a.data.shape_keys.animation_data.action.fcurves.find(key.path_from_id("value"))
    assert [tuple(p.co) for p in curve.keyframe_points] == [(1.0, 0.0), (24.0, 1.0)]
    scene.frame_set(24)
    assert abs(key.value - 1) < 1e-6
    api.animate_morph(a, 10, 30, ping_pong=True)
    curve = a.data.shape_keys.animation_data.action.fcurves.find(key.path_from_id("value"))
    assert [tuple(p.co) for p in curve.keyframe_points] == [(10.0, 0.0), (20.0, 1.0), (30.0, 0.0)], "replaced"
    scene.frame_set(20)
    assert abs(key.value - 1) < 1e-6
    scene.frame_set(30)
    assert abs(key.value) < 1e-6


# -- transfer -------------------------------------------------------------------------------------------

def test_transfer_operator_copies_every_kind():
    a, b = _pair()
    mesh = a.data
    co = maps.positions(mesh)
    loops = _get(mesh.loops, "vertex_index", 1, np.int32)
    _new_uv(mesh, "UVMap", co[loops, :2])
    mesh.color_attributes.new("paint", 'BYTE_COLOR', 'CORNER').data.foreach_set("color", _colours(co)[loops].ravel())
    mesh.attributes.new("height", 'FLOAT', 'POINT').data.foreach_set("value", co[:, 2].astype(np.float32))
    group = a.vertex_groups.new(name="top")
    group.add([int(i) for i in np.flatnonzero(co[:, 2] > 0.5)], 1.0, 'REPLACE')
    bpy.context.scene.consistent_maps.transfer_source = a
    select([b])
    for kind in ('uv_maps', 'color_attributes', 'vertex_groups', 'attributes', 'normals'):
        assert bpy.ops.consistent_maps.transfer(kind=kind) == {'FINISHED'}, kind
    target = b.data
    assert "UVMap" in target.uv_layers and len(target.uv_layers["UVMap"].data) == len(target.loops)
    paint = target.color_attributes["paint"]
    assert paint.domain == 'CORNER' and paint.data_type == 'BYTE_COLOR'
    height = _get(target.attributes["height"].data, "value", 1)
    # B is A stretched and the maps are close to vertex i <-> i (0.97 measured with 3 features)
    assert np.corrcoef(height, maps.positions(target)[:, 2])[0, 1] > 0.9
    assert [g.name for g in b.vertex_groups] == ["CM:tip", "CM:left", "CM:right", "top"], "features not copied"
    assert target.has_custom_normals
    assert api.sphere(b) is not None, "layers leave the result current"


def test_transfer_errors_leave_everything_untouched():
    a, b = _pair()
    c = with_features(load(BALL, "C"))
    api.compute([c], effort=0)  # a computation of its own: no common map with A
    before = [snapshot(obj) for obj in (a, b, c)] + [len(b.data.uv_layers)]
    cases = [((a, c), {"uv_maps": ()}, "not computed together"),
             ((a, b), {"uv_maps": ["nothing"]}, "has no UV map 'nothing'"),
             ((a, b), {"color_attributes": ["nothing"]}, "has no colour attribute"),
             ((a, b), {"vertex_groups": ["nothing"]}, "has no vertex group"),
             ((a, b), {"attributes": ["cm_sphere"]}, "internal"),
             ((a, a), {}, "onto itself")]
    for (source, target), layers, fragment in cases:
        try:
            api.transfer(source, target, **layers)
            raise AssertionError(f"expected an error with '{fragment}'")
        except api.MapError as e:
            assert fragment in str(e), (fragment, str(e))
    bpy.context.scene.consistent_maps.transfer_source = a
    select([b])
    expect_error(bpy.ops.consistent_maps.transfer, "no uv maps", kind='uv_maps')
    assert [snapshot(obj) for obj in (a, b, c)] + [len(b.data.uv_layers)] == before


def _spiked_pair():
    """The ball and a copy drawn out into a spike over its top (the same vertex order and features), computed as
    one set: the map of the copy onto the ball squeezes the spike and keeps the bottom."""
    a = with_features(load(BALL, "Ball"))
    b = load(BALL, "Spiked", location=(3, 0, 0))
    co = maps.positions(b.data)
    low, high = co[:, 2].min(), co[:, 2].max()
    t = np.clip((co[:, 2] - (low + 0.6 * (high - low))) / (0.4 * (high - low)), 0, 1)
    co[:, 2] += 3 * (high - low) * t ** 4
    b.data.vertices.foreach_set("co", co.astype(np.float32).ravel())
    b.data.update()
    with_features(b)
    make_set([a, b])
    api.compute([a, b], effort=0)
    return a, b


def _face_energy(obj):
    """Per face, the energy its "Map distortion" colour shows (4 white ... 64 red; nan for magenta, folded)."""
    from consistent_maps import distortion
    rgba = _get(obj.data.color_attributes[distortion.NAME].data, "color", 4)
    starts = _get(obj.data.polygons, "loop_start", 1, np.int64)
    g, b = rgba[starts, 1], rgba[starts, 2]
    t = np.where(b > 0, (1 - b) / 2, 1 - g / 2)
    return np.where(rgba[starts, 0] > 0.99, 4 * 2 ** (4 * t), np.nan)


def test_show_distortion_colours_where_the_map_stretches():
    from consistent_maps import distortion
    shown = distortion.colours(np.array([4.0, 16, 64, 500, np.nan, 4]), np.array([0, 0, 0, 0, 0, 1], bool))
    assert np.allclose(shown, [[1, 1, 1, 1], [1, 1, 0, 1], [1, 0, 0, 1], [1, 0, 0, 1], distortion.ZERO_AREA,
                               distortion.FOLDED])
    ball, spiked = _spiked_pair()
    before = snapshot(ball)
    summary = api.show_distortion(spiked, ball)
    assert snapshot(ball) == before and spiked.data.color_attributes.active_color.name == distortion.NAME
    energy = _face_energy(spiked)
    z = maps.positions(ball.data)[:, 2]  # the spike's faces by where they were on the ball
    face_z = np.array([z[list(p.vertices)].mean() for p in spiked.data.polygons])
    low, high = z.min(), z.max()
    bottom, spike = face_z < low + 0.4 * (high - low), face_z > low + 0.85 * (high - low)
    print(f"spiked onto ball: bottom median {np.nanmedian(energy[bottom]):.2f}, spike "
          f"{np.nanmedian(energy[spike]):.2f}; {summary}")
    assert np.nanmedian(energy[bottom]) < 5 < 8 < np.nanmedian(energy[spike])
    assert 4 <= summary["median"] < summary["mean"] and 0 < summary["high_area"] < 0.5
    assert summary["folded"] >= np.isnan(energy).sum()  # a face shows magenta if one of its triangles folds
    # Shown again: the one attribute replaced, not a second added.
    api.show_distortion(spiked, ball)
    assert [c.name for c in spiked.data.color_attributes].count(distortion.NAME) == 1

    other = with_features(load(BALL, "C"))
    api.compute([other], effort=0)  # a computation of its own: no common map with the ball
    before = [snapshot(obj) for obj in (ball, other)]
    try:
        api.show_distortion(other, ball)
        raise AssertionError("expected MapError")
    except api.MapError as e:
        assert "not computed together" in str(e), str(e)
    bpy.context.scene.consistent_maps.transfer_source = None
    select([spiked])
    expect_error(bpy.ops.consistent_maps.show_distortion, "choose the source")
    bpy.context.scene.consistent_maps.transfer_source = ball
    spiked.data.color_attributes.remove(spiked.data.color_attributes[distortion.NAME])
    assert bpy.ops.consistent_maps.show_distortion() == {'FINISHED'}
    assert spiked.data.color_attributes.active_color.name == distortion.NAME
    assert [snapshot(obj) for obj in (ball, other)] == before


def test_morph_errors_leave_everything_untouched():
    a, b = _pair()
    c = with_features(load(BALL, "C"))
    settings = bpy.context.scene.consistent_maps
    settings.morph_target = c
    select([a])
    before = [snapshot(obj) for obj in (a, b, c)]
    expect_error(bpy.ops.consistent_maps.morph, "has no result")
    expect_error(bpy.ops.consistent_maps.animate_morph, "no morph key")
    try:
        api.morph(a, b, 'sideways')
        raise AssertionError("bad alignment must be refused")
    except api.MapError as e:
        assert "Unknown alignment" in str(e)
    b.data.vertices[0].co.x += 0.01  # B's result is stale now
    before = [snapshot(obj) for obj in (a, b, c)]
    settings.morph_target = b
    expect_error(bpy.ops.consistent_maps.morph, "stale")
    assert [snapshot(obj) for obj in (a, b, c)] == before


# -- visual check ---------------------------------------------------------------------------------------

SHEET_COLUMNS, SHEET_ROWS, CELL = 6, 4, 200


def _extreme_features(obj):
    """Top, bottom, front, back, left, right: the extreme vertices along the axes (both meshes are y-up)."""
    co = maps.positions(obj.data)
    for name, axis, sign in (("top", 1, 1), ("bottom", 1, -1), ("front", 2, 1), ("back", 2, -1),
                             ("left", 0, -1), ("right", 0, 1)):
        api.add_feature(obj, name, int(np.argmax(sign * co[:, axis])))


def _frame_pixels(scene, path):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(path))
    pixels = np.empty(CELL * CELL * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(CELL, CELL, 4)  # rows bottom to top


def test_render_morph_contact_sheet():
    """The shipped Spot morphing into the shipped penguin over 24 frames (Workbench, coloured by Spot's
    original position): out/blender/morph_sheet-<version>.png, frames left to right, top to bottom."""
    spot = load(ROOT / "examples" / "meshes" / "spot_low.obj", "Spot")
    penguin = load(ROOT / "examples" / "meshes" / "penguin.obj", "Penguin")
    for obj in (spot, penguin):
        _extreme_features(obj)
    api.compute([spot, penguin], effort=0)
    api.morph(spot, penguin, align='bounds')
    api.animate_morph(spot, 1, SHEET_COLUMNS * SHEET_ROWS)
    spot.data.attributes.new("where", 'FLOAT_COLOR', 'POINT').data.foreach_set(
        "color", _colours(maps.positions(spot.data)).ravel())
    spot.data.attributes.active_color = spot.data.attributes["where"]
    spot.rotation_euler = (np.pi / 2, 0, -3 * np.pi / 4)
    penguin.hide_render = True
    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(camera)
    camera.data.type, camera.data.ortho_scale = 'ORTHO', 2.6
    camera.location, camera.rotation_euler = (0, -5, 0.1), (np.pi / 2, 0, 0)
    scene.camera = camera
    scene.render.engine = 'BLENDER_WORKBENCH'
    scene.display.shading.light = 'STUDIO'
    scene.display.shading.color_type = 'VERTEX'
    scene.render.resolution_x = scene.render.resolution_y = CELL
    scene.render.image_settings.file_format = 'PNG'
    OUT.mkdir(parents=True, exist_ok=True)
    sheet = np.zeros((SHEET_ROWS * CELL, SHEET_COLUMNS * CELL, 4), dtype=np.float32)
    for frame in range(1, SHEET_COLUMNS * SHEET_ROWS + 1):
        scene.frame_set(frame)
        row, column = divmod(frame - 1, SHEET_COLUMNS)
        top = (SHEET_ROWS - 1 - row) * CELL  # image rows run bottom to top
        sheet[top:top + CELL, column * CELL:(column + 1) * CELL] = _frame_pixels(scene, OUT / "morph_frame.png")
    (OUT / "morph_frame.png").unlink()
    image = bpy.data.images.new("morph sheet", SHEET_COLUMNS * CELL, SHEET_ROWS * CELL, alpha=True)
    image.pixels.foreach_set(sheet.ravel())
    image.filepath_raw = str(OUT / f"morph_sheet-{VERSION}.png")
    image.file_format = 'PNG'
    image.save()
    first, last = sheet[-CELL:, :CELL], sheet[:CELL, -CELL:]
    assert np.abs(first - last).mean() > 0.01, "the last frame differs from the first: the morph moved"


# -- database: mean shape and principal components --------------------------------------------------------

def test_pca_of_consistent_remeshes():
    a, b = _pair()
    c = with_features(load(BALL, "C", location=(6, 0, 0)))
    c.data.transform(np.diag([1.3, 1.0, 1.2, 1.0]))
    api.compute([a, b, c], effort=0)
    remeshed = api.remesh([a, b, c], 8)
    positions = np.stack([maps.positions(obj.data) for obj in remeshed])
    before = [snapshot(obj) for obj in remeshed]
    select(remeshed)
    bpy.context.scene.consistent_maps.components = 2
    assert bpy.ops.consistent_maps.pca() == {'FINISHED'}
    mean = bpy.data.objects["Mean shape"]
    assert mean.name in bpy.data.collections["Consistent Maps"].objects
    assert np.allclose(maps.positions(mean.data), positions.mean(axis=0), atol=1e-5)
    keys = mean.data.shape_keys.key_blocks
    assert len(keys) == 3 and keys[1].name.startswith("PC1 (") and keys[1].slider_min == -1
    shares = list(mean[api.EXPLAINED_VARIANCE])
    assert shares[0] >= shares[1] > 0 and abs(sum(shares) - 1) < 1e-6, "3 shapes: 2 components explain all"
    # the members are the mean plus a combination of the components
    deltas = np.stack([_get(key.data, "co", 3) - maps.positions(mean.data) for key in keys[1:]]).reshape(2, -1)
    residual = np.linalg.lstsq(deltas.T, (positions - positions.mean(axis=0)).reshape(3, -1).T, rcond=None)[1]
    assert residual.max() < 1e-6, residual
    assert api.features(mean) == api.features(remeshed[0]), (api.features(mean), api.features(remeshed[0]))
    assert [snapshot(obj) for obj in remeshed] == before, "the remeshes are not modified"


def test_pca_errors():
    a, b = _pair()
    remeshed = api.remesh([a, b], 8)
    for objects, k, fragment in (([a, remeshed[0]], 1, "connectivity"), (remeshed[:1], 1, "at least 2"),
                                 (remeshed, 2, "at most 1")):
        try:
            api.pca(objects, k)
            raise AssertionError(f"expected an error with '{fragment}'")
        except api.RemeshSetError as e:
            assert fragment in str(e), (fragment, str(e))
    assert "Mean shape" not in bpy.data.objects


def test_blend_of_consistent_remeshes():
    a, b = _pair()
    remeshed = api.remesh([a, b], 8)
    select(remeshed[::-1], active=remeshed[1])
    assert bpy.ops.consistent_maps.blend() == {'FINISHED'}
    blend = bpy.data.objects["Blend"]
    keys = blend.data.shape_keys.key_blocks
    assert [k.name for k in keys] == ["Basis", "→ A remesh"]
    assert np.allclose(maps.positions(blend.data), maps.positions(remeshed[1].data))
    assert np.allclose(_get(keys[1].data, "co", 3), maps.positions(remeshed[0].data))
    select([a, remeshed[0]])
    expect_error(bpy.ops.consistent_maps.blend, "does not share the connectivity")


# -- texture transfer -----------------------------------------------------------------------------------------

def _textured(obj, size=64):
    """A gradient image (red along u, green along v, blue 1 to tell covered pixels) as obj's material."""
    image = bpy.data.images.new(f"{obj.name} texture", size, size)
    ramp = (np.arange(size) + 0.5) / size
    pixels = np.ones((size, size, 4), dtype=np.float32)
    pixels[..., 0], pixels[..., 1] = ramp[None, :], ramp[:, None]
    image.pixels.foreach_set(pixels.ravel())
    material = bpy.data.materials.new(f"{obj.name} material")
    material.use_nodes = True
    material.node_tree.nodes.new("ShaderNodeTexImage").image = image
    obj.data.materials.append(material)


def test_bake_texture_between_identical_members_reproduces_the_texture():
    """Copies of one mesh share their map: the source's texture baked into the target's (equal) UV layout
    is the texture itself wherever the layout covers the image (margin 0: padding copies across seams)."""
    source, target = _cactus_pair("cactus0")
    api.compute([source, target], effort=0)
    uv = _cylinder_uv(source.data)
    uv = (uv - uv.min(axis=0)) / np.ptp(uv, axis=0)
    for obj in (source, target):
        _new_uv(obj.data, "UVMap", uv)
    _textured(source)
    bpy.context.scene.consistent_maps.transfer_source = source
    bpy.context.scene.consistent_maps.bake_size = 64
    select([target])
    before = snapshot(target), snapshot(source), bpy.context.scene.render.engine
    assert bpy.ops.consistent_maps.bake_texture() == {'FINISHED'}
    assert bpy.data.images["Cactus other from Cactus 0"].size[:] == (64, 64)
    reported = []
    baked = api.bake_texture(source, target, 64, margin=0, progress=reported.append)  # margin 0: comparable pixels
    assert reported == [0.5, 1.0], "the mapped UVs, then the Cycles bake"
    pixels = np.empty(64 * 64 * 4, dtype=np.float32)
    baked.pixels.foreach_get(pixels)
    pixels = pixels.reshape(64, 64, 4)
    ramp = (np.arange(64) + 0.5) / 64
    covered = pixels[..., 2] > 0.99
    error = max(np.abs(pixels[..., 0] - ramp[None, :])[covered].mean(), np.abs(pixels[..., 1] - ramp[:, None])[covered].mean())
    print(f"  baked texture: {covered.mean() * 100:.0f} % of the pixels covered, mean error {100 * error:.2f} %")
    assert covered.mean() > 0.3 and error < 0.03, (covered.mean(), error)
    assert (snapshot(target), snapshot(source), bpy.context.scene.render.engine) == before
    assert len(bpy.data.objects) == 2, "the temporary bake object is gone"


def test_bake_texture_errors():
    a, b = _pair()
    images = len(bpy.data.images)
    before = [snapshot(a), snapshot(b)]

    def refused(fragment):
        try:
            api.bake_texture(a, b, 64)
            raise AssertionError(f"expected '{fragment}'")
        except api.MapError as e:
            assert fragment in str(e), str(e)
    refused("no image texture")
    refused("no UV map to bake into")
    _textured(a)
    _new_uv(b.data, "UVMap", np.zeros((len(b.data.loops), 2)))
    b.data.vertices[0].co.x += 0.01
    refused("stale")
    assert len(bpy.data.images) == images + 1, "no image but the test's own texture"
    assert snapshot(a)[0] == before[0][0]


# -- normal-map bake --------------------------------------------------------------------------------------

def _smooth(obj):
    obj.data.polygons.foreach_set("use_smooth", np.ones(len(obj.data.polygons), dtype=bool))
    obj.data.update()


def _unit_uv(mesh, name="UVMap"):
    uv = _cylinder_uv(mesh)
    uv = (uv - uv.min(axis=0)) / np.ptp(uv, axis=0)
    _new_uv(mesh, name, uv)
    return uv


def _bumpy_ball(name, location=(0, 0, 0), subdivisions=5):
    """A fine icosphere with smooth bumps (radius 1 +- 0.06), smooth shaded, features at the axes' extremes."""
    import bmesh
    bm = bmesh.new()
    bmesh.ops.create_icosphere(bm, subdivisions=subdivisions, radius=1.0)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    co = maps.positions(mesh)
    bumps = 1 + 0.06 * np.sin(9 * co[:, 0]) * np.sin(9 * co[:, 1]) * np.sin(9 * co[:, 2] + 1)
    mesh.vertices.foreach_set("co", (co * bumps[:, None]).astype(np.float32).ravel())
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    _smooth(obj)
    return obj


def _axis_features(obj):
    co = maps.positions(obj.data)
    for name, axis, sign in (("+x", 0, 1), ("-x", 0, -1), ("+y", 1, 1), ("-y", 1, -1), ("+z", 2, 1), ("-z", 2, -1)):
        api.add_feature(obj, name, int((sign * co[:, axis]).argmax()))


def _decoded(image):
    size = image.size[0]
    pixels = np.empty(size * size * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    return pixels.reshape(size, size, 4)[..., :3].astype(np.float64) * 2 - 1


def _blender_frame_at_centroids(mesh, uv_map):
    """Per loop triangle: (centroid UV, tangent, bitangent, normal) of Blender's tangent space (MikkTSpace,
    mesh.calc_tangents), interpolated at the centroid as the Normal Map node does."""
    mesh.calc_tangents(uvmap=uv_map)
    tangent, normal = _get(mesh.loops, "tangent", 3), _get(mesh.loops, "normal", 3)
    sign = _get(mesh.loops, "bitangent_sign", 1)
    mesh.free_tangents()
    _, corners = meshdata.loop_triangles(mesh)
    t, n = tangent[corners].mean(axis=1), normal[corners].mean(axis=1)
    b = np.sign(sign[corners[:, 0]])[:, None] * np.cross(n, t)
    uv = _get(mesh.uv_layers[uv_map].data, "uv", 2)[corners].mean(axis=1)
    return uv, t, b, n


def _tilt(tangent_space):
    """Degrees between decoded tangent-space normals (..., 3) and (0, 0, 1) (robust to 8-bit z = 1)."""
    return np.degrees(np.arctan2(np.hypot(tangent_space[..., 0], tangent_space[..., 1]), tangent_space[..., 2]))


def _angles(a, b):
    a = a / np.linalg.norm(a, axis=1, keepdims=True)
    b = b / np.linalg.norm(b, axis=1, keepdims=True)
    return np.degrees(np.arccos(np.clip((a * b).sum(axis=1), -1, 1)))


def _shown_at_centroids(image, mesh, uv_map="UVMap"):
    """Per loop triangle: the normal Blender's Normal Map node makes of the image's pixel at the triangle's
    UV centroid (decoded in the MikkTSpace frame interpolated there), and that frame's normal."""
    size = image.size[0]
    uv, t, b, n = _blender_frame_at_centroids(mesh, uv_map)
    pixel = np.clip((uv * size).astype(int), 0, size - 1)
    tangent_space = _decoded(image)[pixel[:, 1], pixel[:, 0]]
    return tangent_space[:, :1] * t + tangent_space[:, 1:2] * b + tangent_space[:, 2:] * n, n, tangent_space


def test_bake_normal_map_onto_an_identical_copy_is_flat():
    """A copy of the same mesh (same shape, same map) already has the source's normals: the baked
    tangent-space map is (0, 0, 1) wherever the layout covers the image, and decoded it gives the copy's own
    normals."""
    source, target = _cactus_pair("cactus0")
    for obj in (source, target):
        _smooth(obj)
    api.compute([source, target], effort=0)
    _unit_uv(target.data)
    before = snapshot(target), snapshot(source), bpy.context.scene.render.engine, len(bpy.data.materials)
    reported = []
    image = api.bake_normal_map(source, target, 128, progress=reported.append)
    assert reported == [0.2, 0.4, 0.6, 0.8, 1.0], "four Cycles bakes, then the source's normals"
    assert image.colorspace_settings.name == 'Non-Color' and image.size[:] == (128, 128)
    deviation = _tilt(_decoded(image))
    shown, own, _ = _shown_at_centroids(image, target.data)
    error = _angles(shown, own)
    print(f"  normal map onto an identical copy: mean {deviation.mean():.2f} deg from (0, 0, 1), "
          f"{(deviation > 2).mean() * 100:.2f} % of the pixels over 2 deg; decoded: {error.mean():.2f} deg from "
          f"the copy's own normals (99 %: {np.percentile(error, 99):.2f})")
    assert deviation.mean() < 1 and np.percentile(deviation, 99) < 2, (deviation.mean(), deviation.max())
    assert error.mean() < 1 and np.percentile(error, 99) < 3, (error.mean(), np.percentile(error, 99))
    assert (snapshot(target), snapshot(source), bpy.context.scene.render.engine, len(bpy.data.materials)) == before
    assert len(bpy.data.objects) == 2 and len(bpy.data.images) == 1, "temporaries are gone"


def test_bake_normal_map_shows_the_sources_normals_in_blenders_tangent_space():
    """Bumps of a fine ball baked onto a coarse ellipsoid: decoding the map in the frame of mesh.calc_tangents
    (as the Normal Map node does) gives the source's normal at the point the map takes each target triangle's
    centroid to, far from the target's own normal where the shapes differ."""
    source = _bumpy_ball("Bumpy", subdivisions=4)
    target = load(BALL, "Ellipsoid", location=(3, 0, 0))
    target.data.transform(np.diag([1.0, 1.6, 0.8, 1.0]))
    _smooth(target)
    for obj in (source, target):
        _axis_features(obj)
    api.compute([source, target], effort=0)
    _unit_uv(target.data)
    shown, n, tangent_space = _shown_at_centroids(api.bake_normal_map(source, target, 256, align='none'),
                                                  target.data)
    from consistent_maps import bake, results
    vertices, _ = meshdata.loop_triangles(target.data)
    directions = results.sphere(target.data)[vertices].mean(axis=1)
    landing = mapping.land(maps.parameterization(source), directions / np.linalg.norm(directions, axis=1,
                                                                                        keepdims=True))
    expected = bake._source_normals_at(source, landing, np.eye(3))
    error, own = _angles(shown, expected), _angles(n, expected)
    print(f"  normal map onto another shape: {error.mean():.2f} deg from the source's normals (95 %: "
          f"{np.percentile(error, 95):.2f}); the target's own normals are {own.mean():.1f} deg off")
    assert error.mean() < 2 and np.percentile(error, 95) < 5 and own.mean() > 8, (
        error.mean(), np.percentile(error, 95), own.mean())
    assert _tilt(tangent_space).mean() > 8, "the map deviates from (0, 0, 1) where the shapes differ"


def test_bake_normal_map_aligned_by_features_undoes_a_rotation():
    """A turned copy: with align='features' its normals, turned back, are the target's own (flat map);
    without alignment they are off by the rotation."""
    from test_addon import _extremes
    source, target = load(BALL, "Turned"), load(BALL, "Target", location=(3, 0, 0))
    angle = np.radians(40)
    source.data.transform(np.array([[np.cos(angle), -np.sin(angle), 0, 0], [np.sin(angle), np.cos(angle), 0, 0],
                                    [0, 0, 1, 0], [0, 0, 0, 1]]))
    vertices = _extremes(target, 6)  # the same vertices on both: the copy's own extremes turned
    for obj in (source, target):
        _smooth(obj)
        with_features(obj, ("a", "b", "c", "d", "e", "f"), vertices)
    api.compute([source, target], effort=0)
    _unit_uv(target.data)
    uv, *_ = _blender_frame_at_centroids(target.data, "UVMap")
    pixel = np.clip((uv * 64).astype(int), 0, 63)
    for align, low, high in (('features', 0, 3), ('none', 20, 45)):
        deviation = _tilt(_decoded(api.bake_normal_map(source, target, 64, align=align))[pixel[:, 1], pixel[:, 0]])
        print(f"  turned copy, align {align!r}: {deviation.mean():.2f} deg from the target's own normals")
        assert low <= deviation.mean() <= high, (align, deviation.mean())


def _normal_pattern(size=128):
    """A tangent-space normal map image (Non-Color) with waves along u and v."""
    ramp = (np.arange(size) + 0.5) / size
    u, v = np.meshgrid(ramp, ramp)  # rows: v
    t = np.stack([0.4 * np.sin(2 * np.pi * 3 * u), 0.4 * np.sin(2 * np.pi * 2 * v), np.ones_like(u)], axis=-1)
    t /= np.linalg.norm(t, axis=-1, keepdims=True)
    image = bpy.data.images.new("waves", size, size, float_buffer=True)
    image.colorspace_settings.name = 'Non-Color'
    pixels = np.concatenate([t * 0.5 + 0.5, np.ones((size, size, 1))], axis=-1)
    image.pixels.foreach_set(pixels.astype(np.float32).ravel())
    return image, t


def _with_normal_map(obj, image):
    material = bpy.data.materials.new(f"{obj.name} bumps")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    normal_map = nodes.new("ShaderNodeNormalMap")
    normal_map.uv_map = "UVMap"
    links.new(texture.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs["Normal"], nodes["Principled BSDF"].inputs["Normal"])
    obj.data.materials.append(material)
    return material


def test_bake_normal_map_carries_the_sources_normal_map():
    """The source's own tangent-space normal map goes along: onto an identical copy with the same UV
    layout, the baked map is the source's normal map image."""
    source, target = _cactus_pair("cactus0")
    for obj in (source, target):
        _smooth(obj)
    api.compute([source, target], effort=0)
    for obj in (source, target):
        _unit_uv(obj.data)
    image, truth = _normal_pattern()
    _with_normal_map(source, image)
    size = 128
    decoded = _decoded(api.bake_normal_map(source, target, size, align='none'))
    uv, *_ = _blender_frame_at_centroids(target.data, "UVMap")
    pixel = np.clip((uv * size).astype(int), 0, size - 1)
    error = _angles(decoded[pixel[:, 1], pixel[:, 0]], truth[pixel[:, 1], pixel[:, 0]])
    print(f"  source's normal map onto an identical copy: mean {error.mean():.2f} deg off "
          f"(95 %: {np.percentile(error, 95):.2f})")
    assert error.mean() < 2 and np.percentile(error, 95) < 5, error.mean()


def test_bake_normal_map_operator_and_errors():
    a, b = _pair()
    images, materials = len(bpy.data.images), len(bpy.data.materials)
    before = [snapshot(a), snapshot(b)]

    def refused(fragment, source=a, target=b, size=64, **options):
        try:
            api.bake_normal_map(source, target, size, **options)
            raise AssertionError(f"expected '{fragment}'")
        except api.MapError as e:
            assert fragment in str(e), str(e)
        assert (len(bpy.data.images), len(bpy.data.materials)) == (images, materials), "nothing created"
    refused("no UV map to bake into")
    _unit_uv(b.data)
    refused("Unknown alignment 'bounds'", align='bounds')
    refused("between 16 and 16384 pixels, not 8", size=8)
    bpy.context.scene.consistent_maps.transfer_source = a
    bpy.context.scene.consistent_maps.bake_size = 32
    select([b])
    assert bpy.ops.consistent_maps.bake_normal_map() == {'FINISHED'}
    assert bpy.data.images["B normals from A"].size[:] == (32, 32)
    bpy.data.images.remove(bpy.data.images["B normals from A"])
    bpy.context.scene.consistent_maps.transfer_source = b
    select([a])  # a has no UV map
    expect_error(bpy.ops.consistent_maps.bake_normal_map, "'A' has no UV map to bake into")
    # Aligning by features needs 3 shared.
    api.delete_feature([a], "tip")
    refused("share 2 placed feature(s)", align='features')
    # Objects from different computations, stale results.
    c = with_features(load(BALL, "C", location=(6, 0, 0)))
    api.compute([c], effort=0)
    refused("were not computed together", target=c)
    _unit_uv(c.data)
    b.data.vertices[0].co.x += 0.01
    refused("stale")
    assert snapshot(a)[:3] == before[0][:3], "the source keeps its result and data"


def _shaded(obj, normal_map=None, uv_map="UVMap"):
    """A grey Principled material, with the normal map image (tangent space of uv_map) when given."""
    material = bpy.data.materials.new(f"{obj.name} grey")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    principled = nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (0.7, 0.7, 0.7, 1)
    principled.inputs["Roughness"].default_value = 0.6
    if normal_map is not None:
        uv = nodes.new("ShaderNodeUVMap")
        uv.uv_map = uv_map
        texture = nodes.new("ShaderNodeTexImage")
        texture.image = normal_map
        node = nodes.new("ShaderNodeNormalMap")
        node.uv_map = uv_map
        links.new(uv.outputs["UV"], texture.inputs["Vector"])
        links.new(texture.outputs["Color"], node.inputs["Color"])
        links.new(node.outputs["Normal"], principled.inputs["Normal"])
    obj.data.materials.clear()
    obj.data.materials.append(material)


def test_render_normal_map_transfer():
    """Thesis Fig. 4.4 in small: the bumps of a fine ball (left) carried as a baked normal map onto a coarse
    ellipsoid of 382 vertices (right; the ellipsoid alone in the middle). Cycles renders
    out/blender/normal_map-<version>.png; the right one must show the bumps the middle one lacks."""
    source = _bumpy_ball("Bumpy", location=(-2.8, 0, 0))  # one object per third of the image
    target = load(BALL, "Ellipsoid", location=(2.8, 0, 0))
    target.data.transform(np.diag([1.3, 1.3, 1.0, 1.0]))
    _smooth(target)
    for obj in (source, target):
        _axis_features(obj)
    api.compute([source, target], effort=0)
    _unit_uv(target.data)
    image = api.bake_normal_map(source, target, 512, align='none')
    plain = bpy.data.objects.new("Plain", target.data.copy())
    bpy.context.scene.collection.objects.link(plain)
    _shaded(source)
    _shaded(plain)
    _shaded(target, image)
    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(camera)
    camera.data.type, camera.data.ortho_scale = 'ORTHO', 8.4
    camera.location, camera.rotation_euler = (0, -8, 0), (np.pi / 2, 0, 0)
    scene.camera = camera
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
    sun.data.energy = 2.5
    sun.rotation_euler = (np.radians(25), 0, 0)  # from above, grazing the front: no shadow on a neighbour
    scene.collection.objects.link(sun)
    scene.render.engine = 'CYCLES'
    scene.cycles.samples, scene.cycles.use_denoising = 16, False
    scene.render.resolution_x, scene.render.resolution_y = 3 * CELL, CELL
    scene.render.image_settings.file_format = 'PNG'
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / f"normal_map-{VERSION}.png"
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    rendered = bpy.data.images.load(str(path))
    pixels = np.empty(3 * CELL * CELL * 4, dtype=np.float32)
    rendered.pixels.foreach_get(pixels)
    grey = pixels.reshape(CELL, 3 * CELL, 4)[..., :3].mean(axis=-1)
    blocks = grey.reshape(CELL // 8, 8, 3 * CELL // 8, 8).mean(axis=(1, 3))  # 8x8 averages: no sampling noise
    middle, right = blocks[:, CELL // 8:2 * CELL // 8], blocks[:, 2 * CELL // 8:]
    inside = (middle > 0.1) & (right > 0.1)  # the lit ellipsoid, the same silhouette in both
    change = np.abs(right - middle)[inside].mean()
    print(f"  rendered {path.name}: the baked normal map changes the ellipsoid's brightness by {change:.3f} on "
          f"average over {inside.sum()} blocks of 8x8 pixels")
    assert inside.sum() > 50 and change > 0.015, (inside.sum(), change)  # without the map: 0.004 (noise)


def test_bake_normal_map_refuses_ngons_in_the_target():
    """Blender has no tangent space on faces of more than 4 corners: a clear message, nothing created; as a
    source (without a normal map of its own) such a mesh is fine."""
    ring = [(np.cos(a), np.sin(a)) for a in np.linspace(0, 2 * np.pi, 6, endpoint=False)]
    faces = [tuple(range(5, -1, -1)), tuple(range(6, 12))] + [(i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6)
                                                             for i in range(6)]
    mesh = bpy.data.meshes.new("Prism")
    mesh.from_pydata([(x, y, z) for z in (-1, 1) for x, y in ring], [], faces)
    prism = bpy.data.objects.new("Prism", mesh)
    bpy.context.scene.collection.objects.link(prism)
    ball = load(BALL, "Ball", location=(3, 0, 0))
    with_features(prism, ("a", "b", "c"), (0, 3, 8))
    with_features(ball, ("a", "b", "c"), (0, 100, 200))
    api.compute([prism, ball], effort=0)
    for obj in (prism, ball):
        obj.data.uv_layers.new(name="UVMap")
    images = len(bpy.data.images)
    try:
        api.bake_normal_map(ball, prism, 32)
        raise AssertionError("n-gons have no tangent space")
    except api.MapError as e:
        assert "'Prism' has faces with more than 4 corners" in str(e) and "Triangulate" in str(e), str(e)
    assert len(bpy.data.images) == images
    assert api.bake_normal_map(prism, ball, 32).size[:] == (32, 32)
