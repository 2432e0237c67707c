"""Consistent parameterization of a set through Python and `cmaps consistent`: features on common points of the
sphere, consistent remeshes, geometry images, the sphere locator that maps points and attributes between members,
and one clear error for every bad input."""
import json
import re

import numpy as np
import pytest

from conftest import SHARED
from test_cli import expect_failure, run
from test_constrained import farthest_points

DEFSPHERE = [SHARED / "sets" / "defsphere" / f"defSphere{i}.ply" for i in (0, 3, 6, 9)]
FACES = sorted((SHARED / "sets" / "faces").glob("*.ply"))
TORUS = SHARED / "higher-genus" / "torus.obj"
GRID, REMESH = 32, 16
MISSING = (2, 5)  # member 2 lacks feature 5


def diagonal(vertices):
    return float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))


@pytest.fixture(scope="module")
def meshes(native):
    return [native.read_mesh(str(path)) for path in DEFSPHERE]


@pytest.fixture(scope="module")
def features(meshes):
    """(members, 8): the same vertices on every member (the set shares vertex order), one missing."""
    table = np.tile(farthest_points(meshes[0][0], 8), (len(meshes), 1))
    table[MISSING] = -1
    return table


@pytest.fixture(scope="module")
def result(native, meshes, features):
    return native.consistent_spherical_parameterization(meshes, features, grid=GRID)


def surfaces(result):
    return [(e["refined_vertices"], e["triangles"], e["refined_sphere"]) for _, _, e in result["members"]]


@pytest.fixture(scope="module")
def remesh(native, result):
    return native.consistent_remesh(surfaces(result), result["feature_locations"], REMESH)


# ---------------------------------------------------------------------------------------------- Python


def test_features_land_on_common_locations(meshes, features, result):
    k = features.shape[1]
    locations = result["feature_locations"]
    assert locations.shape == result["initial_locations"].shape == (k, 3)
    assert np.allclose(np.linalg.norm(locations, axis=1), 1, atol=1e-12)
    assert result["first"] == 0 and result["seconds"] > 0
    assert len(result["members"]) == len(meshes)
    for (vertices, triangles), row, (sphere, stats, extras) in zip(meshes, features, result["members"]):
        present = row >= 0
        assert sphere.shape == vertices.shape
        assert np.abs(sphere[row[present]] - locations[present]).max() <= 1e-15
        assert stats["flipped"] == 0 and stats["bijective"] and stats["efficiency"] > 0.5
        n, s = len(vertices), stats["steiner_vertices"]
        assert extras["refined_vertices"].shape == extras["refined_sphere"].shape == (n + s, 3)
        assert (extras["refined_vertices"][:n] == vertices).all() and (extras["refined_sphere"][:n] == sphere).all()
        assert extras["triangles"].max() == n + s - 1


def test_ground_truth_through_the_locator(native, meshes, result):
    """Vertex i of member 0, mapped onto member j through the common sphere, lands near vertex i of member j."""
    sphere0 = result["members"][0][0]
    for j in range(1, len(meshes)):
        _, _, extras = result["members"][j]
        locator = native.SphereLocator(extras["refined_sphere"], extras["triangles"])
        triangles, barycentric = locator.locate(sphere0)
        mapped = locator.interpolate(extras["refined_vertices"], triangles, barycentric)
        vertices = meshes[j][0]
        assert np.linalg.norm(mapped - vertices, axis=1).mean() < 0.03 * diagonal(vertices)


def test_locator_round_trip(native, result):
    _, _, extras = result["members"][1]
    sphere, triangles, positions = extras["refined_sphere"], extras["triangles"], extras["refined_vertices"]
    locator = native.SphereLocator(sphere, triangles)
    assert (locator.sphere == sphere).all() and (locator.triangles == triangles).all()
    found, barycentric = locator.locate(3 * sphere, threads=1)  # directions need not be unit
    assert found.shape == (len(sphere),) and found.dtype == np.int32 and barycentric.shape == (len(sphere), 3)
    assert ((found >= 0) & (found < len(triangles))).all()
    # Each vertex is found in a triangle it is a corner of, with barycentric coordinates one-hot on it.
    corners = triangles[found]
    one_hot = (corners == np.arange(len(sphere))[:, None]).astype(float)
    assert one_hot.sum(axis=1).min() == 1
    assert np.abs(barycentric - one_hot).max() < 1e-9
    # Interpolating per-vertex values gives them back: (n, d) and (n,) values.
    assert np.abs(locator.interpolate(positions, found, barycentric) - positions).max() < 1e-9 * diagonal(positions)
    ids = np.arange(len(sphere), dtype=float)
    assert np.abs(locator.interpolate(ids, found, barycentric) - ids).max() < 1e-6
    # Random directions: barycentric coordinates are convex and reproduce the direction on the chordal triangle.
    directions = np.random.default_rng(1).normal(size=(10000, 3))
    found, barycentric = locator.locate(directions)
    assert (barycentric >= 0).all() and np.allclose(barycentric.sum(axis=1), 1)
    point = locator.interpolate(sphere, found, barycentric)
    unit = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    assert np.abs(point / np.linalg.norm(point, axis=1, keepdims=True) - unit).max() < 1e-9


def test_consistent_remesh(meshes, features, remesh):
    v = REMESH**2 + 2
    assert remesh["sphere"].shape == (v, 3) and remesh["triangles"].shape == (2 * REMESH**2, 3)
    assert remesh["positions"].shape == (len(meshes), v, 3)
    fv = remesh["feature_vertices"]
    assert fv.shape == (features.shape[1],) and len(set(fv.tolist())) == len(fv)
    # Feature k sits at vertex fv[k] of every remesh, on that member's feature vertex.
    for (vertices, _), row, positions in zip(meshes, features, remesh["positions"]):
        present = row >= 0
        assert np.abs(positions[fv[present]] - vertices[row[present]]).max() < 1e-9 * diagonal(vertices)


def test_octahedral_grid_and_geometry_images(native, remesh, tmp_path):
    sphere, triangles, pixels = native.octahedral_grid(REMESH)
    assert sphere.shape == (REMESH**2 + 2, 3) and triangles.shape == (2 * REMESH**2, 3)
    assert pixels.shape == (REMESH + 1, REMESH + 1) and pixels.dtype == np.int32
    assert set(np.unique(pixels)) == set(range(len(sphere)))
    assert (triangles == remesh["triangles"]).all()
    assert np.allclose(np.linalg.norm(sphere, axis=1), 1)

    positions = remesh["positions"][1]
    image = positions[pixels]
    native.write_geometry_image(tmp_path / "g.npy", image)
    native.write_geometry_image(str(tmp_path / "g.png"), image)
    assert (native.read_geometry_image(tmp_path / "g.npy") == image).all()
    assert (np.load(tmp_path / "g.npy") == image).all()
    png = native.read_geometry_image(tmp_path / "g.png")
    extent = image.max(axis=(0, 1)) - image.min(axis=(0, 1))
    assert (np.abs(png - image) <= extent / 65535 * 0.5 + 1e-12).all()
    vertices, mesh_triangles = native.geometry_image_mesh(image)
    assert (vertices == positions).all() and (mesh_triangles == triangles).all()

    normals = native.vertex_normals(positions, triangles)
    assert normals.shape == positions.shape and np.allclose(np.linalg.norm(normals, axis=1), 1)


def test_parameterize_to_locations_adds_a_member(native, features, result):
    vertices, triangles = native.read_mesh(str(SHARED / "sets" / "defsphere" / "defSphere5.ply"))
    row = features[0].copy()
    row[0] = -1
    sphere, stats, extras = native.parameterize_to_locations(vertices, triangles, row, result["feature_locations"])
    present = row >= 0
    assert np.abs(sphere[row[present]] - result["feature_locations"][present]).max() <= 1e-15
    assert stats["flipped"] == 0 and "refined_sphere" in extras


def test_progress_returning_false_cancels(native, meshes, features):
    calls = []

    def progress(fraction, stage):
        calls.append(fraction)
        return len(calls) < 3

    with pytest.raises(native.Cancelled):
        native.consistent_spherical_parameterization(meshes[:2], features[:2], grid=GRID, progress=progress)


def boundary_loops(triangles):
    """Each boundary loop of a mesh as its vertices in order."""
    directed = {(a, b) for t in triangles.tolist() for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    following = {a: b for a, b in directed if (b, a) not in directed}
    loops = []
    while following:
        start = next(iter(following))
        loop = [start]
        while following[loop[-1]] != start:
            loop.append(following.pop(loop[-1]))
        following.pop(loop[-1])
        loops.append(loop)
    return loops


def test_faces_with_holes(native):
    """The expressions (shared vertex order, 2 holes each): 4 features ring each hole, 4 more inside."""
    meshes = [native.read_mesh(str(path)) for path in FACES[:2]]
    vertices, triangles = meshes[0]
    loops = boundary_loops(triangles)
    assert len(loops) == 2
    ring = [loop[i * len(loop) // 4] for loop in loops for i in range(4)]
    inner = [v for v in farthest_points(vertices, 12) if all(v not in loop for loop in loops)][:4]
    table = np.tile(ring + inner, (2, 1))
    result = native.consistent_spherical_parameterization(meshes, table, grid=GRID)
    for (vertices, _), (sphere, stats, _) in zip(meshes, result["members"]):
        assert stats["flipped"] == 0 and stats["degenerate"] == 0
        assert np.abs(sphere[table[0]] - result["feature_locations"]).max() <= 1e-12
    # Step 7 leaves meshes with holes as they are (its refit does not keep boundaries on their arcs).
    aligned = native.consistent_spherical_parameterization(meshes, table, grid=GRID, align=True)
    for (sphere, _, _), (kept, _, _) in zip(result["members"], aligned["members"]):
        assert (sphere == kept).all()
    # With too few features around a hole: one clear message.
    with pytest.raises(native.InvalidMeshError, match=r"ringed by 2 features"):
        native.consistent_spherical_parameterization(meshes, np.delete(table, [0, 1], axis=1), grid=GRID)


def test_faces_ringed_only(native):
    """Features only on the holes' boundaries (4 each, from index len/4 of each loop as found by
    bench/transfer_benchmark.py): a free vertex beside a feature used to block a boundary vertex's split."""
    meshes = [native.read_mesh(str(FACES[i])) for i in (1, 2)]  # neutral, smile
    table = np.tile([3, 7078, 1742, 5449, 23, 1979, 4553, 6393], (2, 1))
    loops = boundary_loops(meshes[0][1])
    assert sorted(len([v for v in table[0] if v in loop]) for loop in loops) == [4, 4]
    result = native.consistent_spherical_parameterization(meshes, table, grid=GRID)
    for sphere, stats, _ in result["members"]:
        assert stats["flipped"] == 0 and stats["degenerate"] == 0
        assert np.abs(sphere[table[0]] - result["feature_locations"]).max() <= 1e-12


def test_restarts_keep_the_best_run(native, meshes, features, result):
    """Two runs (seeds 1 and 2): the kept one has the higher suitability and is the single run with its seed."""
    both = native.consistent_spherical_parameterization(meshes, features, grid=GRID, restarts=2)
    scores = both["restart_suitability"]
    assert scores.shape == (2,) and both["restart"] == int(np.argmax(scores)) and both["suitability"] == scores.max()
    assert 0.85 < scores.min() and result["restart"] == 0 and result["restart_suitability"].shape == (1,)
    single = native.consistent_spherical_parameterization(meshes, features, grid=GRID, seed=1 + both["restart"])
    for (sphere, _, _), (kept, _, _) in zip(single["members"], both["members"]):
        assert (sphere == kept).all()


def test_align_refits_members_towards_the_first(native, meshes, features, result):
    """Step 7: the first member keeps its map; the others are refitted (kept where the distortion between
    them and the first drops), features still exact (the missing one free), no map folds. Its effect on
    the correspondence is measured on sets/cactus (native tests, BENCHMARKS.md)."""
    aligned = native.consistent_spherical_parameterization(meshes, features, grid=GRID, align=True)
    assert (aligned["members"][0][0] == result["members"][0][0]).all()
    assert any((a[0] != r[0]).any() for a, r in zip(aligned["members"][1:], result["members"][1:]))
    for (sphere, stats, _), row in zip(aligned["members"], features):
        assert stats["flipped"] == 0 and stats["degenerate"] == 0
        present = row >= 0
        assert np.abs(sphere[row[present]] - aligned["feature_locations"][present]).max() <= 1e-12


def test_rejects_bad_input(native, meshes, features):
    two = meshes[:2]
    good = features[:2].copy()
    torus = native.read_mesh(str(TORUS))
    cases = [
        (meshes[:1], good[:1], ValueError, "at least 2 meshes"),
        (two, good[:1], ValueError, "features must have shape (2, k)"),
        (two, good[0], ValueError, "features must have shape (2, k)"),
        (two, np.where(np.arange(8) == 3, 99999, good), native.InvalidMeshError, "features[0][3] is vertex 99999"),
        (two, np.array([good[0], [good[1][0], good[1][1], -1, -1, -1, -1, -1, -1]]), native.InvalidMeshError,
         "fewer than 3 of the features"),
        (two, np.array([np.where(np.arange(8) == 0, -1, good[0]), np.where(np.arange(8) == 1, -1, good[1])]),
         native.InvalidMeshError, "no mesh has every feature"),
        (two, np.array([good[0], np.where(np.arange(8) == 1, good[1][0], good[1])]), native.InvalidMeshError,
         "are both vertex"),
        (two, good.astype(float), TypeError, "must hold integers"),
        ([meshes[0], torus], good, native.InvalidMeshError, "meshes[1]: mesh has genus 1"),
        ([meshes[0], "mesh"], good, TypeError, "meshes[1] must be a (vertices, triangles) pair"),
    ]
    for members, table, error, text in cases:
        with pytest.raises(error) as info:
            native.consistent_spherical_parameterization(members, table, grid=GRID)
        assert text in str(info.value), (text, str(info.value))
    for keywords, text in [({"grid": 33}, "grid must be even"), ({"first": 2}, "first must be -1"),
                           ({"effort": 3}, "effort must be 0, 1 or 2"),
                           ({"restarts": 0}, "restarts must be at least 1")]:
        with pytest.raises(ValueError, match=re.escape(text)):
            native.consistent_spherical_parameterization(two, good, **keywords)


def test_rejects_bad_mapping_input(native, result, tmp_path):
    sphere, _, extras = result["members"][0]
    vertices, triangles = extras["refined_vertices"], extras["triangles"]
    locator = native.SphereLocator(extras["refined_sphere"], triangles)
    with pytest.raises(native.InvalidMeshError, match="non-zero and finite"):
        locator.locate(np.zeros((1, 3)))
    found, barycentric = locator.locate(sphere[:5])
    with pytest.raises(ValueError, match="values has 3 rows"):
        locator.interpolate(vertices[:3], found, barycentric)
    with pytest.raises(IndexError, match="triangles\\[0\\] is -1"):
        locator.interpolate(vertices, np.full(5, -1), barycentric)
    with pytest.raises(ValueError, match="barycentric must have shape \\(5, 3\\)"):
        locator.interpolate(vertices, found, barycentric[:4])
    with pytest.raises(native.InvalidMeshError):
        native.SphereLocator(2 * extras["refined_sphere"], triangles)  # not unit vectors
    with pytest.raises(native.InvalidMeshError, match="is flipped on the sphere"):
        native.SphereLocator(extras["refined_sphere"], triangles[:, ::-1])
    with pytest.raises(ValueError, match="n must be even"):
        native.consistent_remesh(surfaces(result), result["feature_locations"], 15)
    with pytest.raises(ValueError, match="n must be even"):
        native.octahedral_grid(7)
    with pytest.raises(TypeError, match="triple"):
        native.consistent_remesh([(vertices, triangles)], result["feature_locations"], 16)
    with pytest.raises(ValueError, match="must end in .npy or .png"):
        native.write_geometry_image(tmp_path / "g.exr", np.zeros((3, 3, 3)))
    with pytest.raises(ValueError, match="shape \\(n\\+1, n\\+1, 3\\)"):
        native.write_geometry_image(tmp_path / "g.npy", np.zeros((4, 4, 3)))
    with pytest.raises(FileNotFoundError):
        native.read_geometry_image(tmp_path / "missing.npy")
    with pytest.raises(ValueError, match="locations has 3 rows for 8 features"):
        native.parameterize_to_locations(vertices[: len(sphere)], result["members"][0][2]["triangles"][:0],
                                         np.arange(8), np.zeros((3, 3)))


# ---------------------------------------------------------------------------------------------- CLI


def write_features(path, table, names=None):
    names = names or [f"feature {k}" for k in range(table.shape[1])]
    data = {name: [None if v < 0 else int(v) for v in table[:, k]] for k, name in enumerate(names)}
    path.write_text(json.dumps(data))
    return path


@pytest.fixture(scope="module")
def cli(cmaps_binary, features, tmp_path_factory):
    folder = tmp_path_factory.mktemp("consistent")
    feature_file = write_features(folder / "features.json", features)
    out = folder / "out"
    result = run(cmaps_binary, "consistent", *DEFSPHERE, "--features", feature_file, "-o", out,
                 "--grid", GRID, "--remesh", REMESH, "--json")
    assert result.returncode == 0, result.stderr
    return out, json.loads(result.stdout)


def test_help_mentions_consistent(cmaps_binary):
    result = run(cmaps_binary, "--help")
    assert "cmaps consistent IN IN ... --features FILE -o DIR" in result.stdout


def test_cli_json(cli, meshes, result):
    out, report = cli
    m = len(meshes)
    assert report["error"] is None and report["first"] == 0
    assert report["restarts"] == 1 and report["restart"] == 0 and len(report["restart_suitability"]) == 1
    assert report["align"] is False
    assert report["faces"] == [len(t) for _, t in meshes]
    for key in ("stretch_efficiency", "flipped", "steiner_vertices", "bijective"):
        assert len(report[key]) == m
    assert report["flipped"] == [0] * m and all(report["bijective"])
    names = [f"feature {k}" for k in range(8)]
    assert list(report["feature_locations"]) == names
    # The same computation as through Python.
    locations = np.array([report["feature_locations"][n] for n in names])
    assert np.abs(locations - result["feature_locations"]).max() < 1e-9
    expected = [f"{k}.{kind}" for k in range(m) for kind in ("sphere.obj", "refined_sphere.obj", "refined.obj")]
    expected += ["features.json", "remesh_features.json"]
    remeshed = ("remesh.obj", "geometry.npy", "geometry.png", "normals.npy")
    expected += [f"{k}.{kind}" for k in range(m) for kind in remeshed]
    assert sorted(p.split("/")[-1] for p in report["outputs"]) == sorted(expected)
    assert sorted(p.name for p in out.iterdir()) == sorted(expected)


def test_cli_spheres(native, cli, meshes, features):
    out, _ = cli
    common = json.loads((out / "features.json").read_text())
    locations = np.array(list(common.values()))
    for k, ((vertices, triangles), row) in enumerate(zip(meshes, features)):
        sphere, sphere_triangles = native.read_mesh(str(out / f"{k}.sphere.obj"))
        assert sphere.shape == vertices.shape and (sphere_triangles == triangles).all()
        assert np.allclose(np.linalg.norm(sphere, axis=1), 1, atol=1e-12)
        present = row >= 0
        assert np.abs(sphere[row[present]] - locations[present]).max() <= 1e-15
        refined_sphere, refined_triangles = native.read_mesh(str(out / f"{k}.refined_sphere.obj"))
        refined, same_triangles = native.read_mesh(str(out / f"{k}.refined.obj"))
        assert (refined_triangles == same_triangles).all() and (refined[: len(vertices)] == vertices).all()
        assert (refined_sphere[: len(vertices)] == sphere).all()
        report = native.measure_spherical_map(refined, refined_triangles, refined_sphere)
        assert report["flipped"] == 0 and report["bijective"]


def test_cli_remeshes_and_geometry_images(native, cli, meshes, features):
    out, _ = cli
    vertex_of = json.loads((out / "remesh_features.json").read_text())
    fv = np.array(list(vertex_of.values()))
    _, grid_triangles, pixels = native.octahedral_grid(REMESH)
    for k, ((vertices, _), row) in enumerate(zip(meshes, features)):
        positions, triangles = native.read_mesh(str(out / f"{k}.remesh.obj"))
        assert (triangles == grid_triangles).all()  # one connectivity for every member
        present = row >= 0
        assert np.abs(positions[fv[present]] - vertices[row[present]]).max() < 1e-9 * diagonal(vertices)
        geometry = np.load(out / f"{k}.geometry.npy")
        assert geometry.shape == (REMESH + 1, REMESH + 1, 3) and (geometry == positions[pixels]).all()
        png = native.read_geometry_image(out / f"{k}.geometry.png")
        extent = geometry.max(axis=(0, 1)) - geometry.min(axis=(0, 1))
        assert (np.abs(png - geometry) <= extent / 65535 * 0.5 + 1e-12).all()
        normals = np.load(out / f"{k}.normals.npy")
        assert (normals == native.vertex_normals(positions, triangles)[pixels]).all()


@pytest.mark.parametrize("case, reason", [
    ("short list", 'feature "feature 0" lists 3 vertices for 4 meshes'),
    ("unknown vertex", 'feature "feature 2": vertex 99999 is out of range for'),
    ("negative vertex", 'feature "feature 0" in mesh 1 has a negative vertex index -4'),
    ("not a list", 'feature "feature 0" must be a list of one vertex index (or null) per mesh'),
    ("two features", 'features "feature 0" and "feature 1" are both vertex'),
    ("too few on one", "has 2 of the features; every input needs at least 3"),
    ("none complete", "no input has every feature"),
    ("first incomplete", 'lacks feature "feature 5"'),
    ("torus", "torus.obj: mesh has genus 1"),
    ("faces", "is ringed by 0 features"),
    ("one mesh", "consistent needs at least 2 input meshes, got 1"),
    ("odd remesh", "--remesh expects an even resolution, got 15"),
    ("odd grid", "--grid expects an even resolution, got 31"),
    ("first out of range", "--first 4 is out of range"),
    ("no features", "consistent needs --features FILE"),
    ("targets", "consistent takes no --targets"),
    ("remesh elsewhere", "sphere takes no --remesh (only consistent and intersurface do)"),
])
def test_cli_rejects_bad_input(cmaps_binary, tmp_path, features, case, reason):
    table = features.copy()
    inputs, extra, names = list(DEFSPHERE), [], None
    if case == "short list":
        table = table[:3]
    elif case == "unknown vertex":
        table[1, 2] = 99999
    elif case == "negative vertex":
        table[1, 0] = -4
    elif case == "two features":
        table[3, 1] = table[3, 0]
    elif case == "too few on one":
        table[1, 2:] = -1
    elif case == "none complete":
        table[0, 0] = table[1, 1] = table[3, 2] = -1
    elif case == "first incomplete":
        extra = ["--first", "2"]
    elif case == "torus":
        inputs[1] = TORUS
    elif case == "faces":
        inputs = FACES[:2]
        table = np.array([[0, 1, 2]] * 2)
    elif case == "one mesh":
        inputs = inputs[:1]
    elif case == "odd remesh":
        extra = ["--remesh", "15"]
    elif case == "odd grid":
        extra = ["--grid", "31"]
    elif case == "first out of range":
        extra = ["--first", "4"]
    feature_file = write_features(tmp_path / "f.json", table, names)
    if case == "negative vertex":
        data = json.loads(feature_file.read_text())
        data["feature 0"][1] = -4
        feature_file.write_text(json.dumps(data))
    elif case == "not a list":
        data = json.loads(feature_file.read_text())
        data["feature 0"] = 12
        feature_file.write_text(json.dumps(data))
    features_args = [] if case == "no features" else ["--features", feature_file]
    if case == "targets":
        extra = ["--targets", feature_file]
    out = tmp_path / "out"
    if case == "remesh elsewhere":
        result = run(cmaps_binary, "sphere", DEFSPHERE[0], "-o", tmp_path / "s.obj", "--remesh", "4", "--json")
    else:
        result = run(cmaps_binary, "consistent", *inputs, *features_args, "-o", out, "--grid", GRID, *extra, "--json")
    expect_failure(result, reason, json_output=True)
    assert not out.exists()  # nothing written


def test_cli_output_directory_errors(cmaps_binary, tmp_path, features):
    feature_file = write_features(tmp_path / "f.json", features)
    blocker = tmp_path / "file"
    blocker.write_text("")
    result = run(cmaps_binary, "consistent", *DEFSPHERE[:2], "--features", feature_file, "-o", blocker)
    expect_failure(result, "is not a directory")
    result = run(cmaps_binary, "consistent", *DEFSPHERE[:2], "--features", feature_file,
                 "-o", tmp_path / "missing" / "out")
    expect_failure(result, "does not exist")
