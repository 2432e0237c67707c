"""The cmaps command line: results, --json output, and one clear error line for bad input."""
import json
import math
import subprocess

import pytest

from conftest import BAD_FILES, REJECTED, SHARED, rejection_reason

SPOT_LOW = SHARED / "genus0" / "spot_low.obj"


def run(binary, *args):
    return subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True, timeout=600)


def expect_failure(result, reason, json_output=False):
    """Non-zero exit, exactly one 'cmaps: error:' line on stderr naming the reason, and with --json one object."""
    assert result.returncode != 0
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("cmaps: error: ")
    assert reason in lines[0]
    if json_output:
        out = json.loads(result.stdout)
        assert reason in out["error"]
        for key in ("faces", "seconds", "stretch_efficiency", "flipped"):
            assert key in out


def test_help_and_version(cmaps_binary):
    result = run(cmaps_binary, "--help")
    assert result.returncode == 0 and "cmaps sphere IN -o OUT" in result.stdout
    result = run(cmaps_binary, "--version")
    assert result.returncode == 0 and result.stdout.strip() == "cmaps 0.1.0"


def test_check_accepts_a_sphere_like_mesh(cmaps_binary):
    result = run(cmaps_binary, "check", SPOT_LOW)
    assert result.returncode == 0, result.stderr
    assert "829 vertices, 1654 triangles, 1 component, closed, manifold, genus 0" in result.stdout
    assert result.stderr == ""


def test_check_json(cmaps_binary):
    result = run(cmaps_binary, "check", SPOT_LOW, "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["faces"] == 1654 and out["vertices"] == 829 and out["genus"] == 0
    assert out["stretch_efficiency"] is None and out["flipped"] is None and out["error"] is None
    assert out["seconds"] >= 0


@pytest.mark.parametrize("relative", REJECTED)
@pytest.mark.parametrize("command", ["check", "sphere"])
def test_rejects_shared_meshes(cmaps_binary, tmp_path, relative, command):
    output = tmp_path / "out.obj"
    extra = ["-o", output] if command == "sphere" else []
    reason = rejection_reason(relative)
    expect_failure(run(cmaps_binary, command, SHARED / relative, *extra), reason)
    expect_failure(run(cmaps_binary, command, SHARED / relative, *extra, "--json"), reason, json_output=True)
    assert not output.exists()


@pytest.mark.parametrize("bad_file", BAD_FILES, indirect=True, ids=[b[0] for b in BAD_FILES])
@pytest.mark.parametrize("command", ["check", "sphere"])
def test_rejects_bad_files(cmaps_binary, tmp_path, bad_file, command):
    path, reason = bad_file
    extra = ["-o", tmp_path / "out.obj"] if command == "sphere" else []
    expect_failure(run(cmaps_binary, command, path, *extra), reason)
    expect_failure(run(cmaps_binary, command, path, *extra, "--json"), reason, json_output=True)


@pytest.mark.parametrize("command", ["check", "sphere"])
def test_missing_input(cmaps_binary, tmp_path, command):
    missing = tmp_path / "missing.obj"
    extra = ["-o", tmp_path / "out.obj"] if command == "sphere" else []
    expect_failure(run(cmaps_binary, command, missing, *extra, "--json"), f"cannot read '{missing}': no such file",
                   json_output=True)


@pytest.mark.parametrize(
    "args, reason",
    [
        ([], "missing command"),
        (["frobnicate", SPOT_LOW], "unknown command 'frobnicate'"),
        (["sphere", SPOT_LOW], "sphere needs -o OUT"),
        (["sphere", SPOT_LOW, "-o", "x.obj", "--effort", "3"], "--effort expects an integer in [0, 2]"),
        (["sphere", SPOT_LOW, "-o", "x.obj", "--threads", "two"], "--threads expects an integer"),
        (["sphere", SPOT_LOW, "-o", "x.stl"], "must end in .obj, .ply or .off"),
        (["check", SPOT_LOW, "--bogus"], "unknown option '--bogus'"),
    ],
)
def test_usage_errors(cmaps_binary, args, reason):
    result = run(cmaps_binary, *args)
    assert result.returncode == 2
    expect_failure(result, reason)
    expect_failure(run(cmaps_binary, *args, "--json"), reason, json_output=True)


def test_sphere_into_missing_directory(cmaps_binary, tmp_path):
    expect_failure(run(cmaps_binary, "sphere", SPOT_LOW, "-o", tmp_path / "no" / "out.obj"), "does not exist")


def obj_faces(path):
    """Vertex indices of each face line ("f 1//1 2//1 3//1" -> ["1", "2", "3"])."""
    return [[c.split("/")[0] for c in line.split()[1:]] for line in path.read_text().splitlines() if line.startswith("f ")]


def test_sphere_writes_unit_vectors_with_input_connectivity(cmaps_binary, tmp_path):
    output = tmp_path / "spot_sphere.obj"
    result = run(cmaps_binary, "sphere", SPOT_LOW, "-o", output, "--json")
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    out = json.loads(result.stdout)
    assert out["error"] is None
    assert out["faces"] == 1654 and out["vertices"] == 829
    assert out["flipped"] == 0 and out["bijective"] is True
    assert 0 < out["stretch_efficiency"] <= 1
    assert math.isclose(out["spherical_area_sum"], 4 * math.pi, rel_tol=1e-9)

    vertices = [line.split()[1:4] for line in output.read_text().splitlines() if line.startswith("v ")]
    assert len(vertices) == 829
    for v in vertices:
        assert math.isclose(math.hypot(*map(float, v)), 1.0, rel_tol=1e-12)
    assert obj_faces(output) == obj_faces(SPOT_LOW)


def test_sphere_ply_output_and_determinism(cmaps_binary, tmp_path, native):
    first, second = tmp_path / "a.ply", tmp_path / "b.ply"
    for path in (first, second):
        result = run(cmaps_binary, "sphere", SPOT_LOW, "-o", path, "--seed", "7", "--effort", "0", "--threads", "1")
        assert result.returncode == 0, result.stderr
        assert "bijective" in result.stdout
    assert first.read_bytes() == second.read_bytes()
    sphere, triangles = native.read_mesh(first)
    _, input_triangles = native.read_mesh(SPOT_LOW)
    assert (triangles == input_triangles).all()
    assert sphere.shape == (829, 3)
