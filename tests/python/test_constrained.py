"""Constrained spherical parameterization through Python and `cmaps constrained`: features exactly on their
targets, bijective, the refined mesh with its Steiner vertices, and one clear error for every bad input."""
import json
import math

import numpy as np
import pytest

from conftest import SHARED
from test_cli import expect_failure, run

MESHES = {"spot_low": SHARED / "genus0" / "spot_low.obj", "bunny": SHARED / "genus0" / "bunny.off"}
SPOT_LOW = MESHES["spot_low"]

# A rotation (about a non-axis direction), to derive given targets from automatic ones.
_axis = np.array([1.0, 2.0, 3.0]) / math.sqrt(14)
_k = np.array([[0, -_axis[2], _axis[1]], [_axis[2], 0, -_axis[0]], [-_axis[1], _axis[0], 0]])
ROTATION = np.eye(3) + math.sin(0.7) * _k + (1 - math.cos(0.7)) * _k @ _k


def farthest_points(vertices, count):
    """Well-spread features: farthest-point sampling by Euclidean distance, from vertex 0."""
    chosen = [0]
    distance = np.full(len(vertices), np.inf)
    while len(chosen) < count:
        distance = np.minimum(distance, ((vertices - vertices[chosen[-1]]) ** 2).sum(axis=1))
        chosen.append(int(distance.argmax()))
    return np.array(chosen)


@pytest.fixture(scope="module")
def meshes(native):
    return {name: native.read_mesh(str(path)) for name, path in MESHES.items()}


@pytest.fixture(scope="module")
def automatic(native, meshes):
    """Results with automatic targets, per mesh: (features, sphere, stats, extras)."""
    results = {}
    for name, (vertices, triangles) in meshes.items():
        features = farthest_points(vertices, 8)
        results[name] = (features, *native.constrained_spherical_parameterization(vertices, triangles, features))
    return results


def refined_positions(vertices, extras):
    """3D positions of the refined triangulation: input vertices, then Steiner vertices on the surface."""
    ids, weights = extras["steiner_vertices"], extras["steiner_weights"]
    steiner = (weights[:, :, None] * vertices[np.maximum(ids, 0)]).sum(axis=1)
    return np.vstack([vertices, steiner])


def expect_valid(native, vertices, input_triangles, features, sphere, stats, extras, targets):
    n, s = len(vertices), stats["steiner_vertices"]
    assert sphere.shape == (n, 3) and sphere.dtype == np.float64
    assert np.allclose(np.linalg.norm(sphere, axis=1), 1, atol=1e-12)
    # Features land exactly on the targets used, which are the given ones normalized.
    assert extras["targets"].shape == (len(features), 3)
    assert (sphere[features] == extras["targets"]).all()
    assert np.abs(extras["targets"] - targets / np.linalg.norm(targets, axis=1, keepdims=True)).max() <= 1e-12
    assert stats["max_constraint_error"] == 0
    assert stats["flipped"] == 0 and stats["degenerate"] == 0 and stats["bijective"] is True
    assert math.isclose(stats["spherical_area_sum"], 4 * math.pi, rel_tol=1e-9)
    assert 0.5 < stats["efficiency"] <= 1
    # The refined triangulation indexes the input vertices and then the Steiner vertices.
    ids, weights, steiner_sphere = extras["steiner_vertices"], extras["steiner_weights"], extras["steiner_sphere"]
    assert ids.shape == weights.shape == steiner_sphere.shape == (s, 3) and ids.dtype == np.int32
    assert ((ids >= -1) & (ids < n)).all() and (weights[ids == -1] == 0).all()
    assert np.allclose(weights.sum(axis=1), 1, atol=1e-12)
    assert stats["steiner_fraction"] == s / n
    triangles = extras["triangles"]
    assert triangles.dtype == np.int32 and triangles.shape == (stats["refined_faces"], 3)
    assert triangles.min() == 0 and triangles.max() == n + s - 1
    # Each refined triangle lies in one input triangle: its corners' input vertices are that triangle's.
    parent = extras["input_triangle"]
    assert parent.dtype == np.int32 and parent.shape == (len(triangles),)
    corner_ids = np.concatenate([np.where(triangles[:, :, None] < n, triangles[:, :, None], -1),
                                 np.where(triangles[:, :, None] >= n, ids[np.maximum(triangles - n, 0)], -1)], axis=2)
    inside = (corner_ids[:, :, :, None] == input_triangles[parent][:, None, None, :]).any(axis=3) | (corner_ids == -1)
    assert inside.all()
    # Measured independently on the refined mesh, the map is bijective.
    report = native.measure_spherical_map(refined_positions(vertices, extras), triangles, np.vstack([sphere, steiner_sphere]))
    assert report["flipped"] == 0 and report["bijective"]


# ---------------------------------------------------------------------------------------------- Python


@pytest.mark.parametrize("name", MESHES)
def test_automatic_targets(native, meshes, automatic, name):
    vertices, triangles = meshes[name]
    features, sphere, stats, extras = automatic[name]
    expect_valid(native, vertices, triangles, features, sphere, stats, extras, extras["targets"])
    assert stats["faces"] == len(meshes[name][1]) and stats["vertices"] == len(vertices)
    assert stats["seconds"] >= stats["seconds_optimize"] >= 0


def test_automatic_targets_come_from_the_unconstrained_map(native, meshes, automatic):
    features, _, _, extras = automatic["spot_low"]
    unconstrained, _ = native.spherical_parameterization(*meshes["spot_low"])
    assert (extras["targets"] == unconstrained[features]).all()


@pytest.mark.parametrize("name", MESHES)
def test_given_targets(native, meshes, automatic, name):
    vertices, triangles = meshes[name]
    features, _, _, auto_extras = automatic[name]
    # Rotated automatic targets, at several lengths (normalized by the library), as a list of lists.
    targets = (auto_extras["targets"] @ ROTATION.T) * np.linspace(0.5, 3, len(features))[:, None]
    sphere, stats, extras = native.constrained_spherical_parameterization(
        vertices, triangles, features.tolist(), targets.tolist(), seed=3, effort=0, threads=1)
    expect_valid(native, vertices, triangles, features, sphere, stats, extras, targets)


def test_deterministic(native, meshes, automatic):
    features, sphere, stats, extras = automatic["spot_low"]
    again, _, again_extras = native.constrained_spherical_parameterization(*meshes["spot_low"], features, seed=1)
    assert (again == sphere).all()
    for key in extras:
        assert (again_extras[key] == extras[key]).all(), key


@pytest.mark.parametrize(
    "features, targets, error, text",
    [
        ([0, 1], None, "InvalidMeshError", "need at least 3 features, got 2"),
        ([], None, "InvalidMeshError", "need at least 3 features, got 0"),
        ([0, 5, 5], None, "InvalidMeshError", "feature vertex 5 is given twice"),
        ([0, 5, 829], None, "InvalidMeshError", "feature 2 is vertex 829 but the mesh has 829 vertices"),
        ([0, -1, 5], None, "InvalidMeshError", "feature 1 is vertex -1 but the mesh has 829 vertices"),
        ([0, 5, 2**40], None, "InvalidMeshError", f"feature 2 is vertex {2**40} but"),
        ([0, 5, 9], [[1, 0, 0], [0, 1, 0], [2, 0, 0]], "InvalidMeshError", "targets 0 and 2 are equal"),
        ([0, 5, 9], [[1, 0, 0], [0, 1, 0], [np.nan, 0, 1]], "InvalidMeshError", "target 2 is not finite"),
        ([0, 5, 9], [[1, 0, 0], [0, np.inf, 0], [0, 0, 1]], "InvalidMeshError", "target 1 is not finite"),
        ([0, 5, 9], [[1, 0, 0], [0, 1, 0], [0, 0, 0]], "InvalidMeshError", "target 2 is the zero vector"),
        ([0, 5, 9], [[1, 0, 0], [0, 1, 0]], "ValueError", "targets has 2 rows for 3 features"),
        ([0, 5, 9], [1, 0, 0], "ValueError", r"targets must have shape \(n, 3\), got \(3,\)"),
        ([[0, 5, 9]], None, "ValueError", r"features must have shape \(k,\), got \(1, 3\)"),
        ([0.0, 5.0, 9.0], None, "TypeError", "features must hold integers, got dtype float64"),
        ([0, 5, 9], [["a", "b", "c"]] * 3, "TypeError", "targets must hold real numbers"),
    ],
)
def test_rejects_bad_features_and_targets(native, meshes, features, targets, error, text):
    expected = {"InvalidMeshError": native.InvalidMeshError, "ValueError": ValueError, "TypeError": TypeError}[error]
    with pytest.raises(expected, match=text):
        native.constrained_spherical_parameterization(*meshes["spot_low"], features, targets)


def test_rejects_unsupported_mesh_and_options(native, meshes):
    torus = native.read_mesh(str(SHARED / "higher-genus" / "torus.obj"))
    with pytest.raises(native.InvalidMeshError, match="genus 1"):
        native.constrained_spherical_parameterization(*torus, [0, 1, 2])
    with pytest.raises(ValueError, match="effort must be 0, 1 or 2"):
        native.constrained_spherical_parameterization(*meshes["spot_low"], [0, 5, 9], effort=3)
    with pytest.raises(TypeError, match="progress must be a callable"):
        native.constrained_spherical_parameterization(*meshes["spot_low"], [0, 5, 9], progress=1)
    with pytest.raises(TypeError):  # options are keyword-only
        native.constrained_spherical_parameterization(*meshes["spot_low"], [0, 5, 9], None, 1)


def test_progress_is_reported(native, meshes):
    calls = []
    native.constrained_spherical_parameterization(*meshes["spot_low"], [0, 827, 480, 391], effort=0,
                                                  progress=lambda f, stage: calls.append((f, stage)))
    fractions = [f for f, _ in calls]
    assert fractions and all(0 <= f <= 1 for f in fractions) and fractions == sorted(fractions)
    assert all(isinstance(stage, str) and stage for _, stage in calls)


@pytest.mark.parametrize("at", [0.0, 0.35, 0.6])
def test_progress_returning_false_cancels(native, meshes, at):
    calls = []

    def stop(fraction, stage):
        calls.append(fraction)
        return fraction < at

    with pytest.raises(native.Cancelled):
        native.constrained_spherical_parameterization(*meshes["spot_low"], [0, 827, 480, 391], progress=stop)
    assert calls[-1] >= at and all(f < at for f in calls[:-1])


def test_exception_in_progress_propagates(native, meshes):
    class Boom(Exception):
        pass

    def explode(fraction, stage):
        raise Boom(f"boom at {stage}")

    with pytest.raises(Boom, match="boom at"):
        native.constrained_spherical_parameterization(*meshes["spot_low"], [0, 827, 480, 391], progress=explode)


# ------------------------------------------------------------------------------------------------- CLI


def write_json(path, data):
    path.write_text(json.dumps(data))
    return path


def read_output(native, path):
    """(vertices, triangles) of a written mesh. The writers keep doubles exactly, but the PLY reader goes
    through OpenMesh's single-precision points, so PLY values compare only to about 1e-7."""
    return native.read_mesh(str(path))


def test_help_mentions_constrained(cmaps_binary):
    result = run(cmaps_binary, "--help")
    assert result.returncode == 0
    assert "cmaps constrained IN --features FILE [--targets FILE] -o OUT [--refined-mesh PATH]" in result.stdout


@pytest.mark.parametrize("name", MESHES)
def test_cli_automatic_targets(native, cmaps_binary, tmp_path, meshes, automatic, name):
    vertices, triangles = meshes[name]
    features, sphere, stats, extras = automatic[name]
    names = [f"feature_{i}" for i in range(len(features))]
    features_file = write_json(tmp_path / "features.json", dict(zip(names, map(int, features))))
    output, refined = tmp_path / "sphere.obj", tmp_path / "refined.ply"
    result = run(cmaps_binary, "constrained", MESHES[name], "--features", features_file, "-o", output,
                 "--refined-mesh", refined, "--json")
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    out = json.loads(result.stdout)
    n, s = len(vertices), out["steiner_vertices"]
    assert out["error"] is None and out["command"] == "constrained"
    assert out["faces"] == len(triangles) and out["vertices"] == n and out["features"] == 8
    assert out["flipped"] == 0 and out["degenerate"] == 0 and out["bijective"] is True
    assert out["max_constraint_error"] == 0 and out["automatic_targets"] is True
    assert 0.5 < out["stretch_efficiency"] <= 1
    assert out["steiner_fraction"] == s / n
    for key in ("auxiliary_vertices", "retraced_paths", "layout_flips"):
        assert isinstance(out[key], int) and out[key] >= 0
    for key in ("seconds", "seconds_paths", "seconds_simplify", "seconds_optimize"):
        assert out[key] >= 0
    assert list(out["targets"]) == names

    # -o: input vertices in input order, then the Steiner vertices, with the refined faces.
    sphere_out, faces_out = read_output(native, output)
    assert sphere_out.shape == (n + s, 3) and len(faces_out) == out["output_faces"]
    assert out["output_vertices"] == n + s
    assert faces_out.max() == n + s - 1
    assert np.allclose(np.linalg.norm(sphere_out, axis=1), 1, atol=1e-12)
    targets = np.array([out["targets"][k] for k in names])
    assert (sphere_out[features] == targets).all()  # exact: both written with round-trip precision
    # The same computation as through Python (same seed and options).
    assert s == stats["steiner_vertices"]
    assert (sphere_out[:n] == sphere).all() and (sphere_out[n:] == extras["steiner_sphere"]).all()
    assert (faces_out == extras["triangles"]).all()

    # --refined-mesh: the same faces; input positions, Steiner vertices on the surface (PLY: single precision).
    positions, faces_refined = read_output(native, refined)
    assert (faces_refined == faces_out).all()
    assert np.allclose(positions[:n], vertices, rtol=0, atol=1e-6 * np.abs(vertices).max())
    assert np.allclose(positions, refined_positions(vertices, extras), rtol=0, atol=1e-6 * np.abs(vertices).max())
    assert native.measure_spherical_map(positions, faces_refined, sphere_out)["flipped"] == 0


def test_cli_given_targets(native, cmaps_binary, tmp_path, meshes, automatic):
    vertices, _ = meshes["bunny"]
    features, _, _, auto_extras = automatic["bunny"]
    names = ["nose", "tail", "ear tip \u00e9", "paw", "back", "chin", "belly", "side"]
    targets = (auto_extras["targets"] @ ROTATION.T) * 2.5  # not unit length: normalized
    features_file = write_json(tmp_path / "f.json", dict(zip(names, map(int, features))))
    # The targets file lists the names in another order.
    targets_file = write_json(tmp_path / "t.json", {k: list(targets[i]) for i, k in reversed(list(enumerate(names)))})
    output = tmp_path / "sphere.ply"
    result = run(cmaps_binary, "constrained", MESHES["bunny"], "--features", features_file, "--targets", targets_file,
                 "-o", output, "--effort", "0", "--seed", "5", "--threads", "1", "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["error"] is None and out["flipped"] == 0 and out["max_constraint_error"] == 0
    assert out["automatic_targets"] is False and out["refined_mesh"] is None
    used = np.array([out["targets"][k] for k in names])
    assert np.abs(used - targets / 2.5).max() <= 1e-12
    sphere_out, faces_out = read_output(native, output)
    assert len(sphere_out) == len(vertices) + out["steiner_vertices"] and len(faces_out) == out["output_faces"]
    assert np.abs(sphere_out[features] - used).max() <= 1e-7  # PLY: read in single precision

    # Without --json: one summary line on stdout.
    result = run(cmaps_binary, "constrained", MESHES["bunny"], "--features", features_file, "--targets", targets_file,
                 "-o", tmp_path / "again.obj", "--effort", "0")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith(f"wrote {tmp_path / 'again.obj'}: 8 features on their targets")
    assert "0 flipped, bijective" in result.stdout
    sphere_obj, faces_obj = read_output(native, tmp_path / "again.obj")
    assert (sphere_obj[features] == used).all()  # OBJ: exact
    assert (faces_obj == faces_out).all()


SPOT_FEATURES = {"a": 0, "b": 827, "c": 480, "d": 391}
SPOT_TARGETS = {"a": [1, 0, 0], "b": [0, 1, 0], "c": [0, 0, 1], "d": [-1, -1, -1]}

# (features file content, targets file content or None, expected reason); contents are JSON text.
BAD_CONSTRAINTS = [
    ('{"a": 0, "b": 827}', None, "features.json: need at least 3 features, got 2"),
    ('{"a": 0, "b": 827, "c": 827}', None, 'features.json: features "b" and "c" are both vertex 827'),
    ('{"a": 0, "b": 827, "c": 829}', None,
     'features.json: feature "c": vertex 829 is out of range (the mesh has 829 vertices)'),
    ('{"a": 0, "b": 827, "c": -3}', None, 'features.json:1:25: feature "c" has a negative vertex index -3'),
    ('{"a": 0, "b": 827, "c": 1.5}', None, 'feature "c" must be an integer vertex index, got 1.5'),
    ('{"a": 0, "b": 827, "c": "480"}', None, 'feature "c" must be a vertex index, got a string'),
    ('{"a": 0, "b": 827, "c": 99999999999}', None, 'feature "c" has vertex index 99999999999, which is too large'),
    ('[0, 827, 480]', None, 'features.json:1:1: expected a JSON object {"name": vertex_index, ...}, got an array'),
    ('{"a": 0, "b": 827, "c": 480', None, "features.json:1:28: invalid JSON: unexpected end of file, expected ',' or '}'"),
    ('{"a": 0, "b": 827, "c": 480,}', None, "features.json:1:29: invalid JSON: unexpected '}', expected a quoted key"),
    ('{"a": 0, "a": 827, "c": 480}', None, 'features.json:1:10: invalid JSON: key "a" appears twice'),
    ("{'a': 0}", None, "invalid JSON: unexpected ''', expected a quoted key"),
    ("", None, "features.json:1:1: invalid JSON: file is empty"),
    ('{"a": 0, "b": 827, "c": 480} {}', None, "invalid JSON: unexpected '{' after the JSON value"),
    ('{"a": 0,\n "b": 827,\n "c": 0480}', None, "features.json:3:8: invalid JSON: invalid number (leading zero)"),
    (json.dumps(SPOT_FEATURES), '{"a": [1, 0, 0], "b": [0, 1, 0], "c": [0, 0, 1]}', 'feature "d" has no target in targets.json'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "e": [0, 0, -1]}),
     'target "e" in targets.json names no feature in features.json'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "d": [0, 0, 3]}),
     'targets.json: targets "c" and "d" are equal (after normalization)'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "b": [0, float("nan"), 1]}),
     'targets.json: target "b" is not finite'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "b": [0, float("inf"), 1]}),
     'targets.json: target "b" is not finite'),
    (json.dumps(SPOT_FEATURES), '{"a": [1, 0, 0], "b": [0, 1e999, 0], "c": [0, 0, 1], "d": [-1, -1, -1]}',
     'targets.json: target "b" is not finite'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "b": [0, 0, 0]}), 'targets.json: target "b" is the zero vector'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "b": [0, 1]}),
     'target "b" must be an array of 3 numbers [x, y, z], got an array of 2'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "b": [0, "1", 0]}),
     'target "b" must be an array of 3 numbers [x, y, z], got a string at position 1'),
    (json.dumps(SPOT_FEATURES), json.dumps({**SPOT_TARGETS, "b": 1}),
     'target "b" must be an array of 3 numbers [x, y, z], got a number'),
    (json.dumps(SPOT_FEATURES), '{"a": [1, 0, 0], "b": [0, 1, 0] "c": [0, 0, 1]}',
     "targets.json:1:33: invalid JSON: unexpected '\"', expected ',' or '}'"),
    (json.dumps(SPOT_FEATURES), '{"a": [1, 0, 0], "b": [0, 1, 0], "c": [0, 0, 1], "d": [1, 1, 1-]}',
     "targets.json:1:63: invalid JSON: unexpected '-', expected ',' or ']'"),
    (json.dumps(SPOT_FEATURES), '{"a\\x": [1, 0, 0]}', "targets.json:1:4: invalid JSON: invalid escape '\\x' in a string"),
]


@pytest.mark.parametrize("features, targets, reason", BAD_CONSTRAINTS, ids=range(len(BAD_CONSTRAINTS)))
def test_cli_rejects_bad_features_and_targets(cmaps_binary, tmp_path, monkeypatch, features, targets, reason):
    monkeypatch.chdir(tmp_path)  # file names in messages are as given: relative here
    (tmp_path / "features.json").write_text(features)
    extra = []
    if targets is not None:
        (tmp_path / "targets.json").write_text(targets)
        extra = ["--targets", "targets.json"]
    args = ["constrained", SPOT_LOW, "--features", "features.json", *extra, "-o", "out.obj", "--refined-mesh", "r.obj"]
    result = run(cmaps_binary, *args)
    assert result.returncode == 1
    expect_failure(result, reason)
    assert result.stdout == ""
    result = run(cmaps_binary, *args, "--json")
    expect_failure(result, reason, json_output=True)
    out = json.loads(result.stdout)
    assert out["targets"] is None and out["flipped"] is None and out["max_constraint_error"] is None
    assert not (tmp_path / "out.obj").exists() and not (tmp_path / "r.obj").exists()


@pytest.mark.parametrize(
    "args, code, reason",
    [
        (["constrained", SPOT_LOW, "-o", "out.obj"], 2, "constrained needs --features FILE"),
        (["constrained", SPOT_LOW, "--features", "f.json"], 2, "constrained needs -o OUT"),
        (["constrained", SPOT_LOW, "--features", "f.json", "-o", "out.stl"], 2, "must end in .obj, .ply or .off"),
        (["constrained", SPOT_LOW, "--features", "f.json", "-o", "o.obj", "--refined-mesh", "r.txt"], 2,
         "output 'r.txt' must end in .obj, .ply or .off"),
        (["constrained", SPOT_LOW, "-o", "out.obj", "--features"], 2, "--features needs a value"),
        (["sphere", SPOT_LOW, "-o", "out.obj", "--features", "f.json"], 2, "sphere takes no --features"),
        (["check", SPOT_LOW, "--targets", "t.json"], 2, "check takes no --targets"),
        (["constrained", SPOT_LOW, "--features", "missing.json", "-o", "out.obj"], 1,
         "cannot read 'missing.json': no such file"),
        (["constrained", SPOT_LOW, "--features", "f.json", "--targets", "missing.json", "-o", "out.obj"], 1,
         "cannot read 'missing.json': no such file"),
        (["constrained", SHARED / "higher-genus" / "torus.obj", "--features", "f.json", "-o", "out.obj"], 1,
         "mesh has genus 1"),
    ],
)
def test_cli_usage_and_file_errors(cmaps_binary, tmp_path, monkeypatch, args, code, reason):
    monkeypatch.chdir(tmp_path)
    write_json(tmp_path / "f.json", SPOT_FEATURES)
    for extra in ([], ["--json"]):
        result = run(cmaps_binary, args[0], *extra, *args[1:])  # --json first: the last option may lack its value
        assert result.returncode == code
        expect_failure(result, reason, json_output=bool(extra))
    assert not (tmp_path / "out.obj").exists()
