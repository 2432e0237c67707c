"""consistent_maps._native: array validation, exception mapping, progress and cancellation."""
import math
import pathlib
import threading
import time

import numpy as np
import pytest

from conftest import BAD_FILES, REJECTED, SHARED, rejection_reason

SPOT_LOW = SHARED / "genus0" / "spot_low.obj"


@pytest.fixture(scope="module")
def spot_low(native):
    return native.read_mesh(str(SPOT_LOW))


@pytest.fixture(scope="module")
def octahedron():
    vertices = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    triangles = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    return vertices, triangles


def test_package_imports_without_blender():
    import consistent_maps

    assert consistent_maps.bl_info["name"] == "Consistent Maps"
    assert consistent_maps.bl_info["blender"] == (3, 4, 0)


def test_exception_hierarchy(native):
    assert issubclass(native.InvalidMeshError, ValueError)
    assert issubclass(native.MeshIOError, OSError)
    assert issubclass(native.Cancelled, Exception)
    assert native.__version__ == "0.1.0"


def test_read_mesh(native, spot_low):
    vertices, triangles = spot_low
    assert vertices.dtype == np.float64 and vertices.shape == (829, 3)
    assert triangles.dtype == np.int32 and triangles.shape == (1654, 3)
    again, _ = native.read_mesh(pathlib.Path(SPOT_LOW))  # os.PathLike works too
    assert (again == vertices).all()


def test_read_mesh_errors(native, tmp_path):
    with pytest.raises(FileNotFoundError, match="no such file"):
        native.read_mesh(str(tmp_path / "missing.obj"))
    (tmp_path / "empty.off").write_text("")
    with pytest.raises(native.MeshIOError, match="empty"):
        native.read_mesh(str(tmp_path / "empty.off"))
    (tmp_path / "mesh.xyz").write_text("1 2 3\n")
    with pytest.raises(OSError, match="unknown extension"):
        native.read_mesh(str(tmp_path / "mesh.xyz"))


def test_check_mesh(native, spot_low):
    report = native.check_mesh(*spot_low)
    assert report["genus"] == 0 and report["closed"] and report["manifold"]
    assert report["components"] == 1 and report["faces"] == 1654
    assert report["sphere_error"] is None
    assert "genus 0" in report["summary"]


def test_check_mesh_reports_why_a_mesh_is_unsuitable(native):
    report = native.check_mesh(*native.read_mesh(str(SHARED / "higher-genus" / "torus.obj")))
    assert report["genus"] == 1
    assert "genus 1" in report["sphere_error"] and report["pair_map_error"] is None


def test_check_mesh_says_what_an_inter_surface_map_takes(native):
    """'pair_map_error' is None exactly where `cmaps check` says `intersurface` takes the mesh: any genus, holes
    and unused vertices allowed (teapot.off has 4), defects named."""
    for relative in ("higher-genus/teapot.off", "boundary/bunny_holes.obj", "genus0/cow.off"):
        report = native.check_mesh(*native.read_mesh(str(SHARED / relative)))
        assert report["pair_map_error"] is None, (relative, report["pair_map_error"])
    teapot = native.check_mesh(*native.read_mesh(str(SHARED / "higher-genus" / "teapot.off")))
    assert teapot["referenced_vertices"] < teapot["vertices"] and teapot["genus"] == 2
    report = native.check_mesh(*native.read_mesh(str(SHARED / "invalid" / "dino_nonmanifold_edges.off")))
    assert report["pair_map_error"] == ("mesh has 2 non-manifold edges (e.g. edge 15404-15545 is shared by 4 "
                                        "triangles); an inter-surface map needs a manifold surface")


def test_accepts_any_real_vertices_and_integer_triangles(native, octahedron):
    vertices, triangles = octahedron
    for v in (vertices.astype(np.float32), vertices.astype(np.int64), np.asfortranarray(vertices), vertices.tolist()):
        for t in (triangles.astype(np.uint16), triangles.astype(np.int64), triangles[:, [0, 1, 2]], triangles.tolist()):
            assert native.check_mesh(v, t)["genus"] == 0


@pytest.mark.parametrize(
    "vertices, triangles, error, text",
    [
        (np.zeros((6, 2)), None, ValueError, r"vertices must have shape \(n, 3\)"),
        (np.zeros(18), None, ValueError, r"vertices must have shape \(n, 3\)"),
        (None, np.zeros((8, 4), dtype=int), ValueError, r"triangles must have shape \(n, 3\)"),
        (None, np.zeros((8, 3)), TypeError, "triangles must hold integers"),
        (np.array([["a", "b", "c"]]), None, TypeError, "vertices must hold real numbers"),
    ],
)
def test_rejects_bad_arrays(native, octahedron, vertices, triangles, error, text):
    v = octahedron[0] if vertices is None else vertices
    t = octahedron[1] if triangles is None else triangles
    for function in (native.check_mesh, native.spherical_parameterization):
        with pytest.raises(error, match=text):
            function(v, t)


@pytest.mark.parametrize("index, shown", [(-1, "-1"), (6, "6"), (2**40, str(2**40))])
def test_rejects_out_of_range_indices(native, octahedron, index, shown):
    vertices, triangles = octahedron
    bad = triangles.astype(np.int64).copy()
    bad[3, 1] = index
    for function in (native.check_mesh, native.spherical_parameterization):
        with pytest.raises(native.InvalidMeshError, match=f"triangle 3 refers to vertex {shown} but the mesh has 6"):
            function(vertices, bad)


@pytest.mark.parametrize("relative", REJECTED)
def test_rejects_shared_meshes(native, relative):
    vertices, triangles = native.read_mesh(str(SHARED / relative))
    with pytest.raises(native.InvalidMeshError) as error:
        native.spherical_parameterization(vertices, triangles)
    assert rejection_reason(relative) in str(error.value)
    assert native.check_mesh(vertices, triangles)["sphere_error"] == str(error.value)


@pytest.mark.parametrize("bad_file", BAD_FILES, indirect=True, ids=[b[0] for b in BAD_FILES])
def test_rejects_bad_files(native, bad_file):
    path, reason = bad_file
    with pytest.raises((native.InvalidMeshError, native.MeshIOError)) as error:
        native.spherical_parameterization(*native.read_mesh(str(path)))
    assert reason in str(error.value)


def test_rejects_nan_coordinates(native, octahedron):
    vertices, triangles = octahedron
    bad = vertices.copy()
    bad[4, 2] = np.nan
    with pytest.raises(native.InvalidMeshError, match="vertex 4 has a non-finite coordinate"):
        native.spherical_parameterization(bad, triangles)


def test_rejects_one_triangle(native):
    with pytest.raises(native.InvalidMeshError, match="mesh has only 1 triangle"):
        native.spherical_parameterization(np.eye(3), np.array([[0, 1, 2]]))


def test_rejects_empty_mesh(native):
    with pytest.raises(native.InvalidMeshError, match="empty"):
        native.spherical_parameterization(np.zeros((0, 3)), np.zeros((0, 3), dtype=int))


@pytest.mark.parametrize(
    "options, error, text",
    [
        ({"effort": 3}, ValueError, "effort must be 0, 1 or 2"),
        ({"threads": 0}, ValueError, "threads must be at least 1"),
        ({"progress": 42}, TypeError, "progress must be a callable"),
    ],
)
def test_rejects_bad_options(native, octahedron, options, error, text):
    with pytest.raises(error, match=text):
        native.spherical_parameterization(*octahedron, **options)


def test_options_are_keyword_only(native, octahedron):
    with pytest.raises(TypeError):
        native.spherical_parameterization(*octahedron, 1)


# --- Happy path: these need the spherical parameterization itself. ---


def test_spherical_parameterization(native, spot_low):
    vertices, triangles = spot_low
    sphere, stats = native.spherical_parameterization(vertices, triangles, seed=3, effort=0)
    assert sphere.dtype == np.float64 and sphere.shape == vertices.shape
    assert np.allclose(np.linalg.norm(sphere, axis=1), 1.0, atol=1e-12)
    expected_keys = {"efficiency", "l2_stretch", "linf_stretch", "flipped", "degenerate", "spherical_area_sum",
                     "surface_area", "seconds", "seconds_simplify", "seconds_optimize", "faces", "vertices"}
    assert expected_keys <= stats.keys()
    assert stats["flipped"] == 0 and stats["degenerate"] == 0
    assert math.isclose(stats["spherical_area_sum"], 4 * math.pi, rel_tol=1e-9)
    assert 0 < stats["efficiency"] <= 1
    assert stats["faces"] == 1654 and stats["vertices"] == 829

    measured = native.measure_spherical_map(vertices, triangles, sphere)
    for key in ("efficiency", "l2_stretch", "flipped", "spherical_area_sum"):
        assert measured[key] == pytest.approx(stats[key])

    again, _ = native.spherical_parameterization(vertices, triangles, seed=3, effort=0)
    assert (again == sphere).all()


def test_measure_rejects_mismatched_sphere(native, octahedron):
    vertices, triangles = octahedron
    with pytest.raises(ValueError, match="sphere has 5 rows but the mesh has 6 vertices"):
        native.measure_spherical_map(vertices, triangles, vertices[:5])


def test_progress_is_reported(native, spot_low):
    calls = []
    native.spherical_parameterization(*spot_low, effort=0, progress=lambda f, stage: calls.append((f, stage)))
    assert calls, "progress was never called"
    fractions = [f for f, _ in calls]
    assert all(0 <= f <= 1 for f in fractions)
    assert fractions == sorted(fractions)
    assert all(isinstance(stage, str) and stage for _, stage in calls)


def test_progress_returning_false_cancels(native, spot_low):
    calls = []

    def stop(fraction, stage):
        calls.append(fraction)
        return False

    with pytest.raises(native.Cancelled):
        native.spherical_parameterization(*spot_low, progress=stop)
    assert len(calls) == 1


def test_progress_returning_none_continues(native, octahedron):
    sphere, stats = native.spherical_parameterization(*octahedron, progress=lambda f, s: None)
    assert stats["flipped"] == 0


def test_exception_in_progress_propagates(native, spot_low):
    class Boom(Exception):
        pass

    def explode(fraction, stage):
        raise Boom(f"boom at {stage}")

    with pytest.raises(Boom, match="boom at"):
        native.spherical_parameterization(*spot_low, progress=explode)
    # The module is still usable afterwards.
    native.spherical_parameterization(*spot_low, effort=0)


def test_gil_is_released(native):
    vertices, triangles = native.read_mesh(str(SHARED / "genus0" / "spot.obj"))
    ticks = []
    done = threading.Event()

    def ticker():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=ticker)
    thread.start()
    try:
        start = time.perf_counter()
        native.spherical_parameterization(vertices, triangles, effort=0, threads=1)
        end = time.perf_counter()
    finally:
        done.set()
        thread.join()
    during = [t for t in ticks if start < t < end]
    assert end - start < 0.02 or len(during) >= 3, f"{len(during)} ticks in {end - start:.3f} s"


def test_surface_locator(native, spot_low):
    """Points of the surface locate where they are; bad meshes and points are refused."""
    vertices, triangles = spot_low
    locator = native.SurfaceLocator(vertices, triangles)
    rng = np.random.default_rng(2)
    chosen = rng.integers(0, len(triangles), 300)
    weights = rng.dirichlet([1, 1, 1], 300)
    corners = vertices[triangles[chosen]]
    points = np.einsum("qk,qkd->qd", weights, corners)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    found, barycentric, distances = locator.locate(points, threads=2)
    assert found.dtype == np.int32 and barycentric.shape == (300, 3) and (distances < 1e-12).all()
    located = np.einsum("qk,qkd->qd", barycentric, vertices[triangles[found]])
    assert np.abs(located - points).max() < 1e-12
    # Lifted a little off the surface: never farther than the lift (the point it left is that far), and
    # mostly exactly that far (elsewhere a concave neighbour may come nearer).
    offset = 1e-4 * np.ptp(vertices, axis=0).max()
    _, _, distances = locator.locate(points + offset * normals)
    assert distances.max() <= offset * (1 + 1e-9) and np.median(np.abs(distances - offset)) < 1e-9 * offset
    for bad in ((vertices, triangles[:0]), (vertices, triangles + len(vertices))):
        with pytest.raises(native.InvalidMeshError):
            native.SurfaceLocator(*bad)
    with pytest.raises(native.InvalidMeshError, match="non-finite"):
        locator.locate(np.array([[0.0, np.nan, 0.0]]))
