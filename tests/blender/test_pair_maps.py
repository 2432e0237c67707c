"""Two objects of equal genus >= 1 in real Blender: Compute maps them onto each other directly (the
inter-surface map through a consistent partition), and morphs and transfers use that map; what needs a
sphere says so clearly.

Run by run_tests.py after test_maps.py.
"""
import bpy
import numpy as np

from consistent_maps import api, maps, meshdata, native, operators_compute, panels, status
from consistent_maps.transfer import corner_normals
import test_addon
from test_addon import SHARED, BALL, _Layout, expect_error, load, make_set, snapshot
from test_maps import (_angles, _colours, _cylinder_uv, _farthest, _get, _new_uv, _shown_at_centroids, _smooth,
                       _textured, _tilt)

TORUS = SHARED / "higher-genus" / "torus.obj"
KNOT = SHARED / "higher-genus" / "knot.obj"
STRETCH = np.diag([1.5, 1.0, 0.7, 1.0])


def _tori(features=16, stretch=STRETCH):
    """The torus and a stretched copy (same vertex order, so the true map is the identity on indices), with
    `features` farthest-point features placed at the same vertices of both, computed as a pair."""
    a = load(TORUS, "Torus")
    b = load(TORUS, "Stretched", location=(4, 0, 0))
    b.data.transform(stretch)
    for index, vertex in enumerate(_farthest(maps.positions(a.data), features)):
        for obj in (a, b):
            api.add_feature(obj, f"f{index}", vertex)
    make_set([a, b])
    api.compute([a, b], effort=0)
    return a, b


def _diagonal(co):
    return float(np.linalg.norm(co.max(axis=0) - co.min(axis=0)))


def test_pair_of_genus_one_is_computed_and_morphs_onto_the_partner():
    a, b = _tori()
    for obj in (a, b):
        assert api.result_state(obj) == 'CURRENT' and api.sphere(obj) is None
    stats = dict(a.data["cm_stats"])
    assert stats["genus"] == 1 and stats["symmetric_dirichlet"] >= 4 and stats["median_symmetric_dirichlet"] >= 4
    assert 0 <= stats["folded_samples"] < len(a.data.polygons) // 20  # bench, 16 true pairs: 24 of 4,608
    assert stats["bijective"], "the map itself folds nowhere (map_flipped 0)"
    summary = operators_compute._summary({obj.name: dict(obj.data["cm_stats"]) for obj in (a, b)})
    assert "genus 1 onto each other directly" in summary and "the map bijective" in summary, summary
    key = api.morph(a, b, align='none')
    shape = _get(key.data, "co", 3)
    truth = maps.positions(b.data)
    error = np.linalg.norm(shape - truth, axis=1).mean() / _diagonal(truth)
    print(f"torus -> stretched torus, 16 true features: mean error {error:.4f} of the diagonal")
    assert error < 0.05  # measured 1.5 % (bench/intersurface_benchmark.py); unrelated vertices: ~30 %
    for name, vertex in api.features(a).items():  # features land exactly on their partners
        assert np.allclose(shape[vertex], truth[api.features(b)[name]], atol=1e-5), name


def test_pair_transfers_colours_both_ways():
    a, b = _tori()
    colours = _colours(maps.positions(a.data))
    layer = a.data.color_attributes.new("Paint", 'FLOAT_COLOR', 'POINT')
    layer.data.foreach_set("color", colours.ravel())
    api.transfer(a, b, color_attributes=["Paint"])
    got = _get(b.data.color_attributes["Paint"].data, "color", 4)
    assert np.abs(got - colours).mean() < 0.05  # same vertex order: the source's own colours come back


def _u_errors(got, truth):
    """Per corner: how far u is from the truth's, modulo whole turns of the texture."""
    off = np.abs(got[:, 0] - truth[:, 0]) % 1
    return np.minimum(off, 1 - off)


def test_pair_transfers_uvs_per_corner_keeping_seams():
    """UVs with u the angle around the torus's axis and a seam where it wraps. Each corner maps from a point
    of its own face, so an identical copy gets every corner's own UV back, in its own face's chart (with a
    corner taking its vertex's image, faces by the seam came back a whole texture off). On the stretched
    copy u comes back close modulo 1 and no face spans the texture."""
    for stretch in (np.eye(4), STRETCH):
        test_addon.reset()
        a, b = _tori(stretch=stretch)
        uv = _cylinder_uv(a.data, axis=1)  # the torus's axis is y
        _new_uv(a.data, "Seamed", uv)
        api.transfer(a, b, uv_maps=["Seamed"])
        got = _get(b.data.uv_layers["Seamed"].data, "uv", 2)
        spanning = int((np.ptp(got[:, 0].reshape(-1, 3), axis=1) > 0.5).sum())
        print(f"  seamed UVs onto {'an identical' if stretch is not STRETCH else 'the stretched'} copy: "
              f"largest error {np.abs(got - uv).max():.4f}, mean u error {_u_errors(got, uv).mean():.4f} "
              f"(modulo 1), {spanning} faces span the texture")
        assert spanning == 0  # the source's faces span none either
        if stretch is STRETCH:
            assert _u_errors(got, uv).mean() < 0.02  # measured 1.2 %: the map is 2.4 % of the diagonal off
        else:
            assert np.abs(got - uv).max() < 0.01  # measured 1e-4: the corner nudge only


def test_pair_transfer_refuses_stale_and_older_results():
    a, b = _tori(features=3)
    _new_uv(a.data, "UVMap", _cylinder_uv(a.data, axis=1))
    for obj in (a, b):
        assert obj.data.attributes["cm_pair_corner_triangle"].domain == 'CORNER'
    b.data.attributes.remove(b.data.attributes["cm_pair_corner_weights"])  # as stored before corner images
    for fragment in ("predates per-corner maps", "stale"):
        try:
            api.transfer(a, b, uv_maps=["UVMap"])
        except api.MapError as e:
            assert fragment in str(e) and "press Compute again" in str(e), str(e)
        else:
            raise AssertionError(f"expected '{fragment}'")
        b.data.vertices[0].co.x += 0.01  # then B's result is stale
    assert "UVMap" not in b.data.uv_layers


def test_pair_bakes_the_texture_through_the_map():
    """Same UV layout on both tori: the source's texture baked into the target comes back close to itself
    (measured 2.5 %: the map is 2.4 % of the diagonal off the identity on indices, and v spans only the
    torus's thin height; an unrelated map is off by about a third of the range)."""
    a, b = _tori()
    uv = _cylinder_uv(a.data)
    uv = (uv - uv.min(axis=0)) / np.ptp(uv, axis=0)
    for obj in (a, b):
        _new_uv(obj.data, "UVMap", uv)
    _textured(a)
    pixels = np.empty(64 * 64 * 4, dtype=np.float32)
    api.bake_texture(a, b, 64, margin=0).pixels.foreach_get(pixels)
    pixels = pixels.reshape(64, 64, 4)
    ramp = (np.arange(64) + 0.5) / 64
    covered = pixels[..., 2] > 0.99
    error = max(np.abs(pixels[..., 0] - ramp[None, :])[covered].mean(),
                np.abs(pixels[..., 1] - ramp[:, None])[covered].mean())
    print(f"  torus texture through the pair map: {covered.mean() * 100:.0f} % covered, mean error {100 * error:.2f} %")
    assert covered.mean() > 0.3 and error < 0.1, (covered.mean(), error)


def test_genus_one_pair_of_different_shapes_and_zero_features():
    a = load(TORUS, "Torus")
    b = load(KNOT, "Knot", location=(4, 0, 0))
    make_set([a, b])
    assert bpy.ops.consistent_maps.compute() == {'FINISHED'}
    key = api.morph(a, b, align='none')
    shape = _get(key.data, "co", 3)
    knot = maps.positions(b.data)
    assert np.isfinite(shape).all()  # on the knot: inside its bounding box
    assert (shape >= knot.min(axis=0) - 1e-5).all() and (shape <= knot.max(axis=0) + 1e-5).all()


def _cut_holes(obj, vertices):
    """Deletes the vertices (and their faces): one hole around each."""
    import bmesh
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    bmesh.ops.delete(bm, geom=[bm.verts[v] for v in vertices], context='VERTS')
    bm.to_mesh(obj.data)
    bm.free()
    obj.data.update()


def _edge_faces(mesh):
    """{edge key: how many faces share it}."""
    faces_per_edge = {}
    for polygon in mesh.polygons:
        for key in polygon.edge_keys:
            faces_per_edge[key] = faces_per_edge.get(key, 0) + 1
    return faces_per_edge


def _rim_distance(points, mesh):
    """Per point: its distance to the nearest boundary edge of the mesh."""
    co = maps.positions(mesh)
    rim = np.array([key for key, count in _edge_faces(mesh).items() if count == 1], int)
    start, direction = co[rim[:, 0]], co[rim[:, 1]] - co[rim[:, 0]]
    t = np.clip(((points[:, None] - start[None]) * direction[None]).sum(-1) / (direction ** 2).sum(-1)[None], 0, 1)
    return np.linalg.norm(points[:, None] - (start[None] + t[..., None] * direction[None]), axis=-1).min(axis=1)


def test_pair_with_holes_maps_rims_onto_rims():
    """Tori of genus 1 with two holes each (the same vertices deleted): Compute pairs the holes, and the
    morph puts every rim vertex on the partner's rim and follows the true correspondence."""
    a = load(TORUS, "Holed")
    b = load(TORUS, "Holed stretched", location=(4, 0, 0))
    b.data.transform(STRETCH)
    holes = _farthest(maps.positions(a.data), 2)
    for obj in (a, b):
        _cut_holes(obj, holes)
    for index, vertex in enumerate(_farthest(maps.positions(a.data), 16)):
        for obj in (a, b):
            api.add_feature(obj, f"f{index}", vertex)
    make_set([a, b])
    api.compute([a, b], effort=0)
    shape = _get(api.morph(a, b, align='none').data, "co", 3)
    truth = maps.positions(b.data)
    error = np.linalg.norm(shape - truth, axis=1).mean() / _diagonal(truth)
    print(f"holed torus -> holed stretched torus, 16 true features: mean error {error:.4f} of the diagonal")
    assert error < 0.03  # measured 1.1 %; unrelated vertices: ~30 %
    on_rim = _rim_distance(maps.positions(a.data), a.data) < 1e-9
    assert on_rim.sum() == 12  # two rings of 6
    assert (_rim_distance(shape[on_rim], b.data) < 1e-5 * _diagonal(truth)).all()
    # Remeshed through the map, both keep the two holes, their rims on the originals' rims.
    for remesh, obj in zip(api.remesh([a, b], 16), (a, b)):
        co = maps.positions(remesh.data)
        rim = np.unique([key for key, count in _edge_faces(remesh.data).items() if count == 1])
        assert len(rim) >= 6 and (_rim_distance(co[rim], obj.data) < 1e-5 * _diagonal(truth)).all(), remesh.name
        assert len(co) - len(_edge_faces(remesh.data)) + len(remesh.data.polygons) == -2  # genus 1, 2 holes


def _remeshes(originals, vertices):
    """The remeshes the last Remesh made of the originals (in the collection "Consistent Maps"), after checking
    that they share one connectivity of `vertices` vertices and carry the originals' transforms. Returns
    [(object, (n, 3) positions)] in the originals' order."""
    found = [bpy.data.objects[f"{obj.name} remesh"] for obj in originals]
    polygons = [[tuple(p.vertices) for p in remesh.data.polygons] for remesh in found]
    assert all(p == polygons[0] for p in polygons) and len(found[0].data.vertices) == vertices
    for remesh, obj in zip(found, originals):
        assert remesh.users_collection[0].name == "Consistent Maps" and remesh.matrix_world == obj.matrix_world
    return [(remesh, maps.positions(remesh.data)) for remesh in found]


def _normals(points, obj):
    """Per loop triangle of obj: its normal (unnormalized) with its vertices at points."""
    triangles = meshdata.loop_triangles(obj.data)[0]
    corners = points[triangles]
    return np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])


def _centroids(points, obj):
    return points[meshdata.loop_triangles(obj.data)[0]].mean(axis=1)


def _exact_vertices(points, obj):
    """Per point: the index of the vertex of obj at exactly that position, -1 where none is."""
    index = {tuple(co): v for v, co in enumerate(maps.positions(obj.data).astype(np.float32))}
    return np.array([index.get(tuple(p), -1) for p in points.astype(np.float32)])


def test_pair_remeshes_share_one_connectivity():
    """Remesh of a pair mapped directly (genus 1): one mesh simplified to n^2 + 2 vertices, its vertices' images
    giving the other's: the two remeshes share one connectivity (a torus still), each lies on its own
    original (one's vertices are its original's, the other's on its original's surface), features at
    identical indices, few triangles folded; the originals stay as they were."""
    a, b = _tori(features=3)
    before = [snapshot(a), snapshot(b)]
    bpy.context.scene.consistent_maps.resolution = 16
    assert bpy.ops.consistent_maps.remesh() == {'FINISHED'}
    (ra, pa), (rb, pb) = _remeshes([a, b], 258)
    carried = dict(ra["cm_pair_remesh"])
    assert carried == dict(rb["cm_pair_remesh"]) and carried["carrier"] in (a.name, b.name), carried
    assert len(ra.data.polygons) == 2 * 258  # V - E + F = 0: a torus
    exact = [_exact_vertices(pa, a), _exact_vertices(pb, b)]
    assert (exact[0 if carried["carrier"] == a.name else 1] >= 0).all(), "the carrier's remesh: its own vertices"
    for obj, points in ((a, pa), (b, pb)):
        _, _, distances = native.surface_locator(*meshdata.arrays(obj.data)).locate(points)
        assert distances.max() < 1e-5 * _diagonal(maps.positions(obj.data)), obj.name
    for name, vertex in api.features(a).items():
        assert api.features(ra)[name] == api.features(rb)[name]
        assert np.allclose(pa[api.features(ra)[name]], maps.positions(a.data)[vertex], atol=1e-6)
        assert np.allclose(pb[api.features(rb)[name]], maps.positions(b.data)[api.features(b)[name]], atol=1e-5)
    folded = 0
    for remesh, points, obj in ((ra, pa, a), (rb, pb, b)):
        vertices, triangles = meshdata.arrays(obj.data)
        found, _, _ = native.surface_locator(vertices, triangles).locate(_centroids(points, remesh))
        folded += ((_normals(points, remesh) * _normals(vertices, obj)[found]).sum(axis=1) < 0).sum()
    print(f"  torus pair remeshed to 258 vertices: {folded} triangles folded")
    assert folded <= 5
    assert [snapshot(a), snapshot(b)] == before
    # One connectivity: the remeshes blend into each other by a shape key.
    blend = api.blend([ra, rb])
    assert np.allclose(_get(blend.data.shape_keys.key_blocks[f"→ {rb.name}"].data, "co", 3), pb, atol=1e-6)
    # A pair in a set with a third object: remesh the two alone.
    ball = load(BALL, "Ball", location=(-4, 0, 0))
    make_set([a, b, ball])
    expect_error(bpy.ops.consistent_maps.remesh, "remesh the set of those two objects alone")


def test_pair_with_a_loose_vertex_is_mapped_and_the_panel_lists_what_compute_refuses():
    """A torus with a vertex no face uses (higher-genus/teapot.off has 4) is mapped onto its partner like any other
    pair (the native map leaves such vertices out; the add-on used to refuse it as 'genus 1' for the sphere); the
    problems the panel lists are Compute's own: none for the pair, the sphere's with the hint in a set of three."""
    a = load(TORUS, "Torus")
    b = load(TORUS, "Loose", location=(4, 0, 0))
    b.data.vertices.add(1)
    b.data.vertices[-1].co = (0, 3, 0)
    b.data.update()
    for name, vertex in (("f0", 0), ("f1", 700), ("f2", 1500)):
        for obj in (a, b):
            api.add_feature(obj, name, vertex)
    make_set([a, b])
    report = status.of(b).report
    assert report["referenced_vertices"] == report["vertices"] - 1
    layout = _Layout()
    panels._draw_problems(layout, [a, b], False)
    assert layout.labels == [], layout.labels
    bpy.context.scene.consistent_maps.effort = '0'
    assert bpy.ops.consistent_maps.compute() == {'FINISHED'}
    shape = _get(api.morph(b, a, align='none').data, "co", 3)
    assert np.isfinite(shape).all() and len(shape) == len(b.data.vertices)
    assert np.allclose(shape[700], maps.positions(a.data)[700], atol=1e-5)  # a feature lands exactly
    assert len(api.remesh([a, b], 8)[1].data.vertices) == 66  # the loose vertex is no remesh vertex
    ball = load(BALL, "Ball", location=(-4, 0, 0))
    panels._draw_problems(layout, [a, b, ball], False)
    tori = [line for line in layout.labels if "genus 1" in line]
    assert len(tori) == 2 and all("make a set of just those two" in line for line in tori), layout.labels


def test_pair_refuses_what_needs_a_sphere_and_mismatched_sets():
    a, b = _tori(features=3)
    before = [snapshot(a), snapshot(b)]
    bpy.context.view_layer.objects.active = a
    expect_error(bpy.ops.consistent_maps.sphere_preview, "no sphere to show", show=True)
    assert [snapshot(a), snapshot(b)] == before
    # a torus with a genus-0 ball: named, with their genera; a torus in a set of three: the hint
    ball = load(BALL, "Ball", location=(-4, 0, 0))
    for name in ("f0", "f1", "f2"):
        api.add_feature(ball, name, 10 * int(name[1]))
    try:
        api.compute([a, ball], effort=0)
    except api.ComputeError as e:
        assert "genus 1" in str(e) and "'Torus'" in str(e), str(e)
    else:
        raise AssertionError("a torus and a ball were computed")
    try:
        api.compute([a, b, ball], effort=0)
    except api.ComputeError as e:
        assert "make a set of just those two" in str(e), str(e)
    else:
        raise AssertionError("a set of three with tori was computed")
    assert [snapshot(a), snapshot(b)] == before


def test_pair_of_genus_zero_maps_directly_when_asked():
    """Two cactus poses (shared vertex order) with 8 features and Map the Pair Directly: Compute maps them
    through the sphere and directly through a consistent partition and keeps the direct map, which lands
    within 1 % of the truth (measured 0.8 %; through the set's common sphere about 2 %); the morph uses it,
    and what needs a sphere says so."""
    cactus = SHARED / "sets" / "cactus"
    a = load(cactus / "cactus0.ply", "Pose0")
    b = load(cactus / "cactus1.ply", "Pose1", location=(1, 0, 0))
    for index, vertex in enumerate(_farthest(maps.positions(a.data), 8)):
        for obj in (a, b):
            api.add_feature(obj, f"f{index}", vertex)
    make_set([a, b])
    settings = bpy.context.scene.consistent_maps
    settings.effort, settings.pair_map = '0', True
    assert bpy.ops.consistent_maps.compute() == {'FINISHED'}
    stats = dict(a.data["cm_stats"])
    assert stats["genus"] == 0 and stats["method"] == "partition" and api.sphere(a) is None
    shape = _get(api.morph(a, b, align='none').data, "co", 3)
    truth = maps.positions(b.data)
    error = np.linalg.norm(shape - truth, axis=1).mean() / _diagonal(truth)
    print(f"cactus pose 0 -> 1 mapped directly, 8 features: mean error {error:.4f} of the diagonal")
    assert error < 0.012
    expect_error(bpy.ops.consistent_maps.sphere_preview, "no sphere to show", show=True)
    # Remesh goes through the pair's map: the images follow the truth as the map does.
    settings.resolution = 24
    assert bpy.ops.consistent_maps.remesh() == {'FINISHED'}
    (_, pa), (_, pb) = _remeshes([a, b], 24 * 24 + 2)
    exact = [_exact_vertices(pa, a), _exact_vertices(pb, b)]
    carried = 0 if (exact[0] >= 0).all() else 1
    assert (exact[carried] >= 0).all()
    images = (pb, pa)[carried]
    truth = maps.positions((b, a)[carried].data)[exact[carried]]
    remesh_error = np.linalg.norm(images - truth, axis=1).mean() / _diagonal(truth)
    print(f"  cactus pair remeshed to {len(pa)} vertices: images {remesh_error:.4f} of the diagonal from the truth")
    assert remesh_error < 0.015


def _torus_uv(mesh):
    """The torus's own layout, without overlaps (a cylinder's would put the tube's inner and outer halves on one
    another): u the angle about its axis (y), v the angle about the tube, each in [0, 1); a face across a seam
    continues past 1 (outside the image). Returns per loop triangle whether it lies inside the image."""
    co = maps.positions(mesh)
    ring = np.hypot(co[:, 0], co[:, 2])
    angles = np.column_stack([np.arctan2(co[:, 2], co[:, 0]), np.arctan2(co[:, 1], ring - 1)])
    _, corners = meshdata.loop_triangles(mesh)
    vertices = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", vertices)
    uv = ((angles + np.pi) / (2 * np.pi))[vertices[corners]]           # (triangles, 3, 2)
    across = np.ptp(uv, axis=1) > 0.5
    uv = np.where(across[:, None, :] & (uv < 0.5), uv + 1, uv)
    per_loop = np.empty((len(mesh.loops), 2))
    per_loop[corners.ravel()] = uv.reshape(-1, 2)
    _new_uv(mesh, "UVMap", per_loop)
    return ~across.any(axis=1)


def test_pair_bakes_a_normal_map_onto_an_identical_copy_flat():
    """No sphere: a torus onto its identical copy (16 features at the same vertices) has the copy's own normals,
    so the baked tangent-space map is nearly (0, 0, 1): each pixel lands at the source point nearest to its
    chord point between its triangle's corners' images, which the map puts within a few percent of the
    identity. Nothing of either object changes; the temporaries are gone."""
    a, b = _tori(stretch=np.eye(4))
    for obj in (a, b):
        _smooth(obj)
    inside = _torus_uv(b.data)
    before = snapshot(a), snapshot(b), len(bpy.data.objects), len(bpy.data.meshes), len(bpy.data.materials)
    reported = []
    image = api.bake_normal_map(a, b, 128, align='none', progress=reported.append)
    assert reported == [0.2, 0.4, 0.6, 0.8, 1.0], "four Cycles bakes, then the source's normals"
    shown, own, tangent_space = (values[inside] for values in _shown_at_centroids(image, b.data))
    error = _angles(shown, own)
    print(f"  pair normal map onto an identical torus: {_tilt(tangent_space).mean():.2f} deg from (0, 0, 1) at "
          f"the triangles' centroids; decoded {error.mean():.2f} deg from the copy's own normals "
          f"(95 %: {np.percentile(error, 95):.2f})")
    assert error.mean() < 1 and np.percentile(error, 95) < 2, (error.mean(), np.percentile(error, 95))
    assert (snapshot(a), snapshot(b), len(bpy.data.objects), len(bpy.data.meshes), len(bpy.data.materials)) == before


def test_pair_bakes_the_sources_bumps_into_a_normal_map():
    """A bumped torus onto the plain one (same vertex order: the true map is the identity on indices): decoded
    at each target triangle's centroid, the baked map gives the bumped torus's normal at the same triangle's
    centroid, far from the plain torus's own normal."""
    a = load(TORUS, "Bumped")
    b = load(TORUS, "Plain", location=(4, 0, 0))
    co = maps.positions(a.data)
    ring = np.hypot(co[:, 0], co[:, 2])  # the torus's axis is y; the tube circles around the ring of radius 1
    centre = co.copy()
    centre[:, 1] = 0
    centre[:, [0, 2]] *= (1 / ring)[:, None]
    outward = (co - centre) / np.linalg.norm(co - centre, axis=1, keepdims=True)
    angle = np.arctan2(co[:, 2], co[:, 0])
    around = np.arctan2(co[:, 1], ring - 1)
    bumped = co + 0.03 * (np.sin(5 * angle) * np.sin(3 * around))[:, None] * outward
    a.data.vertices.foreach_set("co", bumped.astype(np.float32).ravel())
    a.data.update()
    for index, vertex in enumerate(_farthest(maps.positions(b.data), 16)):
        for obj in (a, b):
            api.add_feature(obj, f"f{index}", vertex)
    make_set([a, b])
    api.compute([a, b], effort=0)
    for obj in (a, b):
        _smooth(obj)
    inside = _torus_uv(b.data)
    image = api.bake_normal_map(a, b, 256, align='none')
    shown, own, tangent_space = (values[inside] for values in _shown_at_centroids(image, b.data))
    normals = corner_normals(a.data)
    _, corners = meshdata.loop_triangles(a.data)
    truth = normals[corners].mean(axis=1)[inside]
    error, plain = _angles(shown, truth), _angles(own, truth)
    print(f"  bumped torus onto the plain one: {error.mean():.2f} deg from the bumped normals (95 %: "
          f"{np.percentile(error, 95):.2f}); the plain torus's own normals are {plain.mean():.2f} deg off")
    # Measured 0.83 deg (95 %: 2.1) against 8.3.
    assert error.mean() < 2 and np.percentile(error, 95) < 5 and plain.mean() > 6, (error.mean(), plain.mean())
