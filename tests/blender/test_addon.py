"""The add-on suite, run in real Blender (3.4 application and bpy 4.x module) by run_tests.py.

Meshes come from ../shared/meshes through the native reader and bpy's data API
(import operators differ between Blender versions). Every test starts from an
empty scene with the add-on registered (reset()).
"""
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time
import zipfile

import bmesh
import bpy
import numpy as np

import consistent_maps
from consistent_maps import _native, api, features, job, overlay, registration, status

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "meshes"
OUT = ROOT / "out" / "blender"
BALL = SHARED / "genus0" / "sphere.obj"  # 382 vertices: quick to map
SPOT = SHARED / "genus0" / "spot_low.obj"
IS_MODULE = not bpy.app.binary_path or "site-packages" in bpy.app.binary_path
VERSION = ".".join(map(str, bpy.app.version))

_loaded = {}


# -- helpers ------------------------------------------------------------------------------------

def reset():
    if bpy.context.object is not None and bpy.context.object.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    if job.current() is not None:
        job.current().cancel()
        while not job.current().done:
            time.sleep(0.01)
        job.finish()
    bpy.ops.wm.read_homefile(use_empty=True)


def load(path, name=None, location=(0, 0, 0)):
    """A new object with the mesh at path (read by the native reader), linked to the scene."""
    if path not in _loaded:
        _loaded[path] = _native.read_mesh(str(path))
    vertices, triangles = _loaded[path]
    mesh = bpy.data.meshes.new(name or path.stem)
    mesh.from_pydata(vertices.tolist(), [], triangles.tolist())
    mesh.update()
    obj = bpy.data.objects.new(name or path.stem, mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def select(objects, active=None):
    bpy.context.view_layer.update()  # new objects get their view layer base
    for obj in bpy.context.view_layer.objects:
        obj.select_set(obj in objects)
    bpy.context.view_layer.objects.active = active or objects[0]


def make_set(objects):
    select(objects)
    assert bpy.ops.consistent_maps.add_selected() == {'FINISHED'}
    return objects


def with_features(obj, names=("tip", "left", "right"), vertices=(0, 100, 200)):
    for name, index in zip(names, vertices):
        api.add_feature(obj, name, index)
    return obj


def expect_error(operator, fragment, **properties):
    """Runs the operator, which must report an error containing fragment."""
    try:
        result = operator(**properties)
    except RuntimeError as e:
        assert fragment.lower() in str(e).lower(), f"expected '{fragment}' in: {e}"
        return str(e)
    raise AssertionError(f"expected an error containing '{fragment}', got {result}")


def snapshot(obj):
    """Everything the add-on could touch on an object, to prove it was left alone."""
    mesh = obj.data
    return (api.result_state(obj), sorted(a.name for a in mesh.attributes), sorted(mesh.keys()),
            [g.name for g in obj.vertex_groups], mesh.shape_keys is not None,
            consistent_maps.meshdata.fingerprint(mesh))


def edit_select_vertices(obj, indices):
    select([obj])
    bpy.ops.object.mode_set(mode='EDIT')
    bm = bmesh.from_edit_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    for v in bm.verts:
        v.select = v.index in indices
    bm.select_flush(True)
    bmesh.update_edit_mesh(obj.data)


def on_unit_sphere(points):
    return np.allclose(np.linalg.norm(points, axis=1), 1, atol=1e-4)


# -- package, manifest, registration -----------------------------------------------------------

def test_manifest_is_a_valid_extension_manifest():
    import tomllib
    manifest = tomllib.loads((ROOT / "blender_manifest.toml").read_text())
    required = {"schema_version": str, "id": str, "version": str, "name": str, "tagline": str,
                "maintainer": str, "type": str, "blender_version_min": str, "license": list}
    for key, kind in required.items():
        assert isinstance(manifest.get(key), kind), f"manifest: '{key}' missing or not a {kind.__name__}"
    assert manifest["schema_version"] == "1.0.0"
    assert manifest["id"] == "consistent_maps" and manifest["type"] == "add-on"
    assert re.fullmatch(r"\d+\.\d+\.\d+", manifest["version"])
    assert manifest["version"] == ".".join(map(str, consistent_maps.bl_info["version"])), "manifest vs bl_info"
    cmake_version = re.search(r"project\(consistent_maps VERSION (\S+)", (ROOT / "CMakeLists.txt").read_text())
    assert cmake_version and cmake_version.group(1) == manifest["version"], "manifest vs CMake project version"
    assert len(manifest["tagline"]) <= 64 and manifest["tagline"][-1] not in ".!?", "tagline rules"
    assert tuple(map(int, manifest["blender_version_min"].split("."))) >= (4, 2, 0)
    assert all(entry.startswith("SPDX:") for entry in manifest["license"])
    assert manifest.get("platforms") == ["linux-x64"]
    assert "permissions" not in manifest, "the add-on uses no network or file access: no permissions"


def _package_zip():
    version = ".".join(map(str, consistent_maps.bl_info["version"]))
    path = pathlib.Path(os.environ.get("CMAPS_ADDON_ZIP", ROOT / "dist" / f"consistent_maps-{version}.zip"))
    assert path.exists(), f"{path} is missing: cmake --build build --target package_addon"
    return path


def test_package_zip_layout():
    names = zipfile.ZipFile(_package_zip()).namelist()
    sources = [f"consistent_maps/{p.name}" for p in (ROOT / "addon" / "consistent_maps").glob("*.py")]
    for required in ["consistent_maps/blender_manifest.toml", *sources]:
        assert required in names, f"{required} not in the zip (rebuild it: cmake --build build --target package_addon)"
    assert any(re.fullmatch(r"consistent_maps/_native\..*\.so", n) for n in names), "compiled module missing"
    assert all(n.startswith("consistent_maps/") for n in names), "one folder at the zip root"
    assert not any("__pycache__" in n or n.endswith(".pyc") for n in names)


def _run(command, env=None):
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=120)
    output = done.stdout + done.stderr
    assert done.returncode == 0, f"{command[:3]} failed:\n{output[-3000:]}"
    return output


def test_package_zip_installs():
    """3.4: Preferences > Add-ons > Install and enable, in a fresh Blender with its own user scripts.
    4.2+ (bpy module): Blender's extension tool validates and installs the zip as an extension,
    and a fresh Python registers the installed package."""
    package = _package_zip()
    with tempfile.TemporaryDirectory() as scripts:
        if IS_MODULE:
            tool = pathlib.Path(bpy.utils.resource_path('LOCAL')) / "scripts/addons_core/bl_pkg/cli/blender_ext.py"
            _run([sys.executable, str(tool), "validate", str(package)])
            _run([sys.executable, str(tool), "install-files", "--local-dir", scripts,
                  "--blender-version", VERSION, str(package)])
            code = ("import bpy, sys;"
                    f"sys.path.insert(0, {scripts!r});"
                    "import consistent_maps; consistent_maps.register();"
                    f"assert consistent_maps.__file__.startswith({scripts!r});"
                    "assert hasattr(bpy.types.Scene, 'consistent_maps');"
                    "import consistent_maps.api, consistent_maps._native;"
                    "consistent_maps.unregister();"  # the bpy module hangs at exit with classes registered
                    "print('INSTALLED-OK')")
            assert "INSTALLED-OK" in _run([sys.executable, "-c", code])
        else:
            code = ("import bpy, addon_utils, sys;"
                    f"bpy.ops.preferences.addon_install(filepath={str(package)!r});"
                    "addon_utils.enable('consistent_maps', default_set=True, handle_error=None);"
                    "assert hasattr(bpy.types.Scene, 'consistent_maps');"
                    "import consistent_maps.api, consistent_maps._native;"
                    "assert consistent_maps.__file__.startswith(bpy.utils.user_resource('SCRIPTS'));"
                    "print('INSTALLED-OK')")
            env = dict(os.environ, BLENDER_USER_SCRIPTS=scripts, BLENDER_USER_CONFIG=scripts)
            assert "INSTALLED-OK" in _run([bpy.app.binary_path, "-b", "--factory-startup", "--python-exit-code", "1",
                                           "--python-expr", code], env)


def test_package_imports_without_bpy_and_quickly():
    """The package, its API and the worker-thread job import in plain Python (bpy blocked), in under 1 s."""
    code = ("import sys, time; sys.modules['bpy'] = None; sys.modules['bmesh'] = None;"
            f"sys.path.insert(0, {str(ROOT / 'addon')!r}); start = time.perf_counter();"
            "import consistent_maps, consistent_maps.api, consistent_maps.job, consistent_maps.status;"
            "print('IMPORT-SECONDS', time.perf_counter() - start)")
    seconds = float(_run([sys.executable, "-c", code]).split("IMPORT-SECONDS")[1])
    assert seconds < 1.0, f"import took {seconds:.2f} s"


def test_register_unregister():
    assert hasattr(bpy.types.Scene, "consistent_maps") and hasattr(bpy.types, "CM_PT_main")
    consistent_maps.unregister()
    assert not hasattr(bpy.types.Scene, "consistent_maps")
    assert not hasattr(bpy.types, "CM_PT_main") and not hasattr(bpy.types, "CONSISTENT_MAPS_OT_compute")
    assert not any(registration._forget_cached_features in h for h in registration.HANDLERS)
    consistent_maps.register()
    assert hasattr(bpy.types.Scene, "consistent_maps") and hasattr(bpy.types, "CONSISTENT_MAPS_OT_compute")


def test_every_operator_is_undoable():
    operators = [c for c in registration.CLASSES if issubclass(c, bpy.types.Operator)]
    assert len(operators) == 20
    for cls in operators:
        if cls.bl_idname != "consistent_maps.cancel":  # cancelling changes no data
            assert 'UNDO' in cls.bl_options, cls.bl_idname


def test_feature_names_are_not_remembered_between_uses():
    """Blender remembers operator properties; a remembered name would move the last feature."""
    for op in ("add_feature", "rename_feature", "delete_feature", "select_feature"):
        properties = getattr(bpy.ops.consistent_maps, op).get_rna_type().properties
        assert properties["name"].is_skip_save, op


def test_overlay_is_not_installed_in_background():
    assert bpy.app.background and overlay._handles == []


# -- the set ------------------------------------------------------------------------------------

def test_set_operators():
    expect_error(bpy.ops.consistent_maps.add_selected, "select one or more mesh")
    a, b, c = load(BALL, "A"), load(BALL, "B"), load(BALL, "C")
    make_set([a, b])
    select([b, c])
    bpy.ops.consistent_maps.add_selected()  # B is already there: only C is added
    settings = bpy.context.scene.consistent_maps
    assert [m.object.name for m in settings.members] == ["A", "B", "C"]
    settings.active_member = 2
    assert bpy.ops.consistent_maps.move_member(direction='UP') == {'FINISHED'}
    assert [m.object.name for m in settings.members] == ["A", "C", "B"] and settings.active_member == 1
    bpy.ops.consistent_maps.move_member(direction='DOWN')
    assert [m.object.name for m in settings.members] == ["A", "B", "C"]
    settings.active_member = 0
    assert bpy.ops.consistent_maps.move_member(direction='UP') == {'CANCELLED'}
    assert bpy.ops.consistent_maps.remove_member() == {'FINISHED'}
    assert [m.object.name for m in settings.members] == ["B", "C"]
    assert "A" in bpy.data.objects, "removing from the set keeps the object"


# -- features -----------------------------------------------------------------------------------

def test_feature_api():
    a, b = load(BALL, "A"), load(BALL, "B")
    assert api.add_feature(a, "  nose ", 5) == "nose"
    assert a.vertex_groups.get("CM:nose") and api.features(a) == {"nose": 5}
    api.add_feature(a, "nose", 7)  # moves it
    assert api.features(a) == {"nose": 7}
    for bad, message in ((("", 1), "empty"), (("x", 10**6), "no vertex"), (("ear", 7), "already feature")):
        try:
            api.add_feature(a, *bad)
            raise AssertionError(f"add_feature{bad} should fail")
        except api.FeatureError as e:
            assert message in str(e), e
    assert features.next_free_name([a]) == "F1"
    api.add_feature(a, "F1", 8)
    assert features.next_free_name([a, b]) == "F2"
    assert api.copy_feature_names(a, [b]) == 2
    assert features.memberships(b) == {"nose": [], "F1": []} and api.features(b) == {}
    assert api.rename_feature([a, b], "F1", "chin") == "chin"
    assert set(features.memberships(b)) == {"nose", "chin"} and api.features(a)["chin"] == 8
    api.add_feature(b, "ear", 9)
    try:
        api.rename_feature([a, b], "chin", "ear")
        raise AssertionError("renaming onto an existing name should fail")
    except api.FeatureError as e:
        assert "already has a feature named 'ear'" in str(e)
    assert api.delete_feature([a, b], "chin") == 2 and "chin" not in features.memberships(b)


def test_features_read_fresh_where_no_handler_keeps_a_cache_fresh():
    """The add-on's handlers keep its feature cache fresh only while it is registered: a script using the api
    without registering (examples/blender_example.py) edits groups and loads files with nothing to invalidate
    it, so it reads the groups each time; registered, a new object at a freed one's address must not take its
    features before the next handler call (the group names are part of the key)."""
    a = load(BALL, "A")
    api.add_feature(a, "nose", 5)
    assert api.features(a) == {"nose": 5}
    a.vertex_groups.clear()  # no handler has run since
    assert api.features(a) == {}
    consistent_maps.unregister()
    try:
        api.add_feature(a, "nose", 5)
        a.vertex_groups["CM:nose"].remove([5])
        a.vertex_groups["CM:nose"].add([6], 1.0, 'REPLACE')
        assert api.features(a) == {"nose": 6}
    finally:
        consistent_maps.register()


def test_feature_problems_are_plain():
    a, b = load(BALL, "A"), load(BALL, "B")
    with_features(a)
    api.add_feature(b, "tip", 0)
    b.vertex_groups.new(name="CM:left")
    b.vertex_groups["CM:left"].add([1, 2], 1.0, 'REPLACE')
    problems = "\n".join(api.feature_problems([a, b]))
    assert "'left' on 'B' has 2 vertices" in problems
    assert "'left', 'right' placed only on 'A'" in problems
    assert "'B' has 1 of the set's features ('tip'); each object needs at least 3" in problems
    assert "'A' has 1 of the set's features" in problems
    assert api.feature_problems([a]) == []


def _extremes(obj, count=5):
    """Vertices at the extremes of x, y and z: well-spread features on the ball."""
    co = consistent_maps.maps.positions(obj.data)
    picks = [int(co[:, 0].argmax()), int(co[:, 0].argmin()), int(co[:, 1].argmax()), int(co[:, 1].argmin()),
             int(co[:, 2].argmax()), int(co[:, 2].argmin())]
    return picks[:count]


def _gapped_set():
    """A, B, C (B and C other shapes) with features F1..F5; B lacks F5 and C lacks F4 (no group at all)."""
    objects = [load(BALL, "A"), load(BALL, "B", location=(3, 0, 0)), load(BALL, "C", location=(6, 0, 0))]
    objects[1].data.transform(np.diag([1.0, 1.6, 0.8, 1.0]))
    objects[2].data.transform(np.diag([0.7, 1.0, 1.3, 1.0]))
    vertices = _extremes(objects[0])
    for obj, lacks in zip(objects, (None, "F5", "F4")):
        for k, vertex in enumerate(vertices):
            if f"F{k + 1}" != lacks:
                api.add_feature(obj, f"F{k + 1}", vertex)
    return objects


def test_features_may_be_missing_on_some_objects():
    a, b, c = _gapped_set()
    assert api.feature_problems([a, b, c]) == []
    assert api.feature_names([a, b, c]) == ["F1", "F2", "F3", "F4", "F5"]
    make_set([a, b, c])
    bpy.context.scene.consistent_maps.effort = '0'
    assert bpy.ops.consistent_maps.compute() == {'FINISHED'}
    locations = consistent_maps.results.feature_locations(bpy.context.scene)
    assert list(locations) == ["F1", "F2", "F3", "F4", "F5"]
    for obj, count in ((a, 5), (b, 4), (c, 4)):
        sphere = api.sphere(obj)
        assert on_unit_sphere(sphere) and consistent_maps.results.stats(obj.data)["bijective"]
        placed = api.features(obj)
        assert len(placed) == count
        for name, vertex in placed.items():
            assert np.allclose(sphere[vertex], locations[name], atol=1e-5), (obj.name, name)
    # B and C share F1-F3: maps between them and alignment by their shared features work.
    key = api.morph(b, c, align='features')
    assert key.name == "→ C" and len(key.data) == len(b.data.vertices)
    remeshed = api.remesh([a, b, c], 8)
    assert all(list(api.features(r)) == ["F1", "F2", "F3", "F4", "F5"] for r in remeshed)


def test_missing_features_what_is_still_required():
    a, b, c = _gapped_set()
    objects = [a, b, c]
    make_set(objects)
    before = [snapshot(obj) for obj in objects]
    # A feature on a single object corresponds to nothing.
    api.add_feature(c, "lonely", 7)
    message = expect_error(bpy.ops.consistent_maps.compute, "'lonely' placed only on 'C'")
    assert "at least one other object" in message
    api.delete_feature([c], "lonely")
    # Every object needs 3 of the set's features.
    api.delete_feature([c], "F3")
    api.delete_feature([c], "F2")
    expect_error(bpy.ops.consistent_maps.compute, "'C' has 2 of the set's features ('F1', 'F5'); each object needs "
                                                  "at least 3")
    api.add_feature(c, "F2", _extremes(a)[1])
    api.add_feature(c, "F3", _extremes(a)[2])
    # One object must carry all of them.
    api.delete_feature([a], "F1")
    api.add_feature(a, "F6", 40)
    api.add_feature(c, "F6", 40)
    message = expect_error(bpy.ops.consistent_maps.compute, "No object has all 6 features of the set")
    assert "place 'F1' on 'A'" in message, message
    # An empty group is a feature still to place (not silently left out).
    api.add_feature(a, "F1", _extremes(a)[0])
    c.vertex_groups.new(name="CM:F4")
    message = expect_error(bpy.ops.consistent_maps.compute, "'F4' is not placed on 'C'")
    assert "delete the empty group" in message
    assert [snapshot(obj)[:3] for obj in objects] == [s[:3] for s in before], "no results, nothing stored"


class _Layout:
    """Records the labels a panel's draw code makes (panels cannot draw in background mode)."""

    def __init__(self, labels=None):
        self.labels = [] if labels is None else labels

    def label(self, text="", **_):
        self.labels.append(text)

    def operator(self, *_args, **_):
        return type("Properties", (), {})()

    def prop(self, *_args, **_):
        pass

    def column(self, **_):
        return _Layout(self.labels)

    row = box = column


def test_panels_describe_a_set_with_gaps():
    a, b, c = _gapped_set()
    make_set([a, b, c])
    from consistent_maps import panels
    layout = _Layout()
    panels._draw_status(layout, b, [a, b, c])
    panels._draw_missing(layout, b, [a, b, c])
    assert "4 of the set's 5 (without F5)" in layout.labels, layout.labels
    assert "Optional here (left free without):" in layout.labels and "F5" in layout.labels, layout.labels
    layout = _Layout()
    panels._draw_status(layout, a, [a, b, c])
    assert not any("of the set's" in label for label in layout.labels), "A has all of them"


def test_add_feature_operator_in_edit_mode():
    a = load(BALL, "A")
    make_set([a])
    edit_select_vertices(a, {3, 4})
    expect_error(bpy.ops.consistent_maps.add_feature, "exactly one vertex (2 selected)")
    edit_select_vertices(a, {3})
    assert bpy.ops.consistent_maps.add_feature() == {'FINISHED'}  # no name: the next free one
    edit_select_vertices(a, {10})
    assert bpy.ops.consistent_maps.add_feature(name="ear") == {'FINISHED'}
    assert api.features(a) == {"F1": 3, "ear": 10}, "read in Edit Mode"
    bpy.ops.object.mode_set(mode='OBJECT')
    assert api.features(a) == {"F1": 3, "ear": 10}, "kept after leaving Edit Mode"
    assert bpy.ops.consistent_maps.add_feature.poll() is False, "needs Edit Mode"


def test_rename_delete_copy_select_operators():
    a, b = load(BALL, "A"), load(BALL, "B")
    with_features(a)
    make_set([a, b])
    select([a])
    assert bpy.ops.consistent_maps.copy_feature_names() == {'FINISHED'}
    assert set(features.memberships(b)) == {"tip", "left", "right"} and api.features(b) == {}
    assert bpy.ops.consistent_maps.rename_feature(name="tip", new_name="nose") == {'FINISHED'}
    assert "nose" in features.memberships(a) and "nose" in features.memberships(b)
    expect_error(bpy.ops.consistent_maps.rename_feature, "no object has a feature named", name="x", new_name="y")
    a.vertex_groups.active_index = a.vertex_groups["CM:left"].index
    assert bpy.ops.consistent_maps.delete_feature() == {'FINISHED'}  # the active feature, this object only
    assert "left" not in features.memberships(a) and "left" in features.memberships(b)
    assert bpy.ops.consistent_maps.delete_feature(name="left", everywhere=True) == {'FINISHED'}
    assert "left" not in features.memberships(b)
    expect_error(bpy.ops.consistent_maps.delete_feature, "no feature 'left'", name="left")
    assert bpy.ops.consistent_maps.select_feature(name="right") == {'FINISHED'}
    assert a.mode == 'EDIT'
    selected = [v.index for v in bmesh.from_edit_mesh(a.data).verts if v.select]
    assert selected == [200], selected
    bpy.ops.object.mode_set(mode='OBJECT')
    select([b])
    expect_error(bpy.ops.consistent_maps.select_feature, "no placed feature 'right'", name="right")
    bpy.context.scene.consistent_maps.members.clear()
    expect_error(bpy.ops.consistent_maps.copy_feature_names, "no other object")


def test_overlay_points_follow_features_and_preview():
    a, b = load(BALL, "A"), load(BALL, "B", location=(3, 0, 0))
    make_set([with_features(a), with_features(b)])
    points = overlay.feature_points(bpy.context)
    assert len(points) == 6
    by_name = {}
    for position, colour, name in points:
        by_name.setdefault(name, set()).add(colour)
    assert all(len(colours) == 1 for colours in by_name.values()), "same name, same colour"
    assert abs(points[3][0].x - points[0][0].x - 3) < 1e-5, "world space"
    api.compute([a, b], effort=0)
    api.show_sphere(a)
    bpy.context.view_layer.update()
    radius = 0.5 * max(a.dimensions)
    centre = np.mean([list(v) for v in a.bound_box], axis=0)
    for position, _, _ in overlay.feature_points(bpy.context)[:3]:
        assert abs(np.linalg.norm(np.array(position) - centre) - radius) < 0.05 * radius, "on the preview sphere"


# -- compute ------------------------------------------------------------------------------------

def test_compute_operator_stores_results():
    a, b = with_features(load(BALL, "A")), with_features(load(BALL, "B"))
    make_set([a, b])
    bpy.context.scene.consistent_maps.effort = '0'
    bpy.context.scene.consistent_maps.restarts = 2
    bpy.context.scene.consistent_maps.align = True
    assert bpy.ops.consistent_maps.compute() == {'FINISHED'}
    tasks = api.prepare([a, b])
    outcome = api.run(tasks, api.feature_names([a, b]), effort=0, restarts=2, align=True)  # the panel's settings
    for obj, member in zip((a, b), outcome.members):
        assert np.allclose(api.sphere(obj), member[0], atol=1e-6)  # stored as float32
    for obj in (a, b):
        sphere = api.sphere(obj)
        assert sphere.shape == (len(obj.data.vertices), 3) and on_unit_sphere(sphere)
        attribute = obj.data.attributes["cm_sphere"]
        assert (attribute.domain, attribute.data_type) == ('POINT', 'FLOAT_VECTOR')
        stats = consistent_maps.results.stats(obj.data)
        assert stats["bijective"] and 0 < stats["efficiency"] <= 1 and stats["seconds"] > 0
        assert status.of(obj).result == "CURRENT"
        assert obj.data.shape_keys is None, "no preview unless asked"


def test_compute_invoke_runs_synchronously_in_background():
    a = load(BALL, "A")
    make_set([a])
    assert bpy.ops.consistent_maps.compute('INVOKE_DEFAULT') == {'FINISHED'}
    assert api.result_state(a) == "CURRENT"


def test_compute_triangulates_ngons():
    """A hexagonal prism of quads and n-gons: one sphere position per original vertex."""
    ring = [(np.cos(a), np.sin(a)) for a in np.linspace(0, 2 * np.pi, 6, endpoint=False)]
    vertices = [(x, y, z) for z in (-1, 1) for x, y in ring]
    faces = [tuple(range(5, -1, -1)), tuple(range(6, 12))] + [(i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6)
                                                             for i in range(6)]
    mesh = bpy.data.meshes.new("prism")
    mesh.from_pydata(vertices, [], faces)
    obj = bpy.data.objects.new("prism", mesh)
    bpy.context.scene.collection.objects.link(obj)
    arrays = consistent_maps.meshdata.extract(obj)
    assert arrays.triangles.shape == (2 * 4 + 6 * 2, 3) and arrays.vertices.shape == (12, 3)
    api.compute([obj], effort=0)
    sphere = api.sphere(obj)
    assert sphere.shape == (12, 3) and on_unit_sphere(sphere)
    assert len(mesh.polygons) == 8, "the mesh itself stays as it was"


def test_stale_detection():
    a = load(BALL, "A")
    api.compute([a], effort=0)
    assert api.result_state(a) == "CURRENT" and status.of(a).result == "CURRENT"
    a.data.vertices[5].co.x += 0.01
    assert api.result_state(a) == "STALE" and status.of(a).result == "STALE"
    assert api.sphere(a) is None
    try:
        api.show_sphere(a)
        raise AssertionError("a stale result must not be previewed")
    except api.PreviewError as e:
        assert "stale" in str(e)
    a.data.vertices[5].co.x -= 0.01
    assert api.result_state(a) == "CURRENT", "undoing the edit makes it current again"
    api.compute([a], effort=0)
    assert api.result_state(a) == "CURRENT"


def test_save_and_reload_keeps_results():
    a = with_features(load(BALL, "A"))
    make_set([a])
    api.compute([a], effort=0)
    api.show_sphere(a)
    sphere = api.sphere(a).copy()
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "results.blend")
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.wm.read_homefile(use_empty=True)
        assert "A" not in bpy.data.objects
        bpy.ops.wm.open_mainfile(filepath=path)
    a = bpy.data.objects["A"]
    assert [m.object for m in bpy.context.scene.consistent_maps.members] == [a]
    assert api.result_state(a) == "CURRENT" and np.array_equal(api.sphere(a), sphere)
    assert api.features(a) == {"tip": 0, "left": 100, "right": 200}
    assert consistent_maps.results.stats(a.data)["bijective"]
    assert a.data.shape_keys.key_blocks["CM Sphere"].value == 1.0
    assert len(api.remesh([a], 8)[0].data.vertices) == 66, "the parameterized surface is saved too"


def test_sphere_preview_operator():
    a = load(BALL, "A")
    make_set([a])
    expect_error(bpy.ops.consistent_maps.sphere_preview, "no result yet", show=True)
    before = snapshot(a)
    bpy.ops.consistent_maps.compute()
    assert bpy.ops.consistent_maps.sphere_preview(show=True) == {'FINISHED'}
    keys = a.data.shape_keys.key_blocks
    assert [k.name for k in keys] == ["Basis", "CM Sphere"] and keys["CM Sphere"].value == 1
    co = np.array([list(k.co) for k in keys["CM Sphere"].data])
    centre = (co.max(axis=0) + co.min(axis=0)) / 2
    distances = np.linalg.norm(co - centre, axis=1)
    assert np.allclose(distances, distances[0], rtol=1e-3), "the key is a sphere"
    assert api.result_state(a) == "CURRENT", "the preview does not make the result stale"
    assert bpy.ops.consistent_maps.sphere_preview(show=False) == {'FINISHED'}
    assert a.data.shape_keys is None, "hiding removes the keys the preview added"
    assert snapshot(a)[3:] == before[3:]
    bpy.context.scene.consistent_maps.members.clear()
    expect_error(bpy.ops.consistent_maps.sphere_preview, "set is empty")


def test_threaded_job_leaves_the_main_thread_free_and_applies():
    spot = with_features(load(SPOT, "Spot"))
    tasks = api.prepare([spot])
    running = job.start(tasks, api.feature_names([spot]), {"effort": 0, "threads": 1})
    assert bpy.ops.consistent_maps.compute.poll() is False, "one computation at a time"
    longest, last = 0.0, time.perf_counter()
    while not running.done:
        time.sleep(0.005)
        now = time.perf_counter()
        longest, last = max(longest, now - last), now
    assert running.error is None and not running.cancelled and running.fraction > 0.5
    assert longest < 0.1, f"main thread blocked for {longest:.3f} s"
    assert api.result_state(spot) == "NONE", "nothing is stored before apply"
    api.apply(running.tasks, running.outcome)
    job.finish()
    assert api.result_state(spot) == "CURRENT" and on_unit_sphere(api.sphere(spot))


def test_cancel_operator_stops_the_job_and_changes_nothing():
    spot = with_features(load(SPOT, "Spot"))
    before = snapshot(spot)
    assert bpy.ops.consistent_maps.cancel.poll() is False
    running = job.start(api.prepare([spot]), [], {"effort": 1, "threads": 1})
    while running.stage == "starting" and not running.done:  # wait for the first progress report
        time.sleep(0.005)
    assert bpy.ops.consistent_maps.cancel() == {'FINISHED'}
    while not running.done:
        time.sleep(0.01)
    assert running.cancelled and running.outcome is None
    job.finish()
    assert snapshot(spot) == before


def test_cancel_after_the_computation_ended_still_changes_nothing():
    """Cancel pressed after the last progress report, before the result is applied: it is dropped."""
    spot = with_features(load(SPOT, "Spot"))
    before = snapshot(spot)
    running = job.start(api.prepare([spot]), [], {"effort": 0, "threads": 1})
    while not running.done:
        time.sleep(0.01)
    assert running.error is None and running.outcome is not None and not running.cancelled
    assert bpy.ops.consistent_maps.cancel() == {'FINISHED'}
    assert running.cancelled and running.outcome is None
    job.finish()
    assert snapshot(spot) == before and api.result_state(spot) == "NONE"


def test_loading_a_file_drops_a_running_job():
    spot = load(SPOT, "Spot")
    running = job.start(api.prepare([spot]), [], {"effort": 2, "threads": 1})
    bpy.ops.wm.read_homefile(use_empty=True)
    assert job.current() is None and bpy.ops.consistent_maps.compute.poll()
    while not running.done:
        time.sleep(0.01)


def test_cancel_through_progress_callback():
    a = load(BALL, "A")
    before = snapshot(a)
    try:
        api.compute([a], effort=0, progress=lambda fraction, stage: False)
        raise AssertionError("returning False must cancel")
    except api.Cancelled:
        pass
    assert snapshot(a) == before


def test_apply_refuses_a_mesh_edited_during_the_computation():
    a = load(BALL, "A")
    tasks = api.prepare([a])
    outcome = api.run(tasks, [], effort=0)
    a.data.vertices[0].co.z += 0.1
    before = snapshot(a)
    try:
        api.apply(tasks, outcome)
        raise AssertionError("apply must refuse")
    except api.ComputeError as e:
        assert "changed during the computation" in str(e)
    assert snapshot(a) == before


def _consistent_pair():
    a = with_features(load(BALL, "A"))
    b = load(BALL, "B", location=(3, 0, 0))
    b.data.transform(np.diag([1.0, 1.6, 0.8, 1.0]))  # another shape, same features
    with_features(b)
    make_set([a, b])
    bpy.context.scene.consistent_maps.effort = '0'
    assert bpy.ops.consistent_maps.compute() == {'FINISHED'}
    return a, b


def test_compute_of_a_set_is_consistent():
    a, b = _consistent_pair()
    locations = consistent_maps.results.feature_locations(bpy.context.scene)
    assert list(locations) == ["tip", "left", "right"]
    for obj in (a, b):
        sphere = api.sphere(obj)
        assert on_unit_sphere(sphere)
        for name, vertex in api.features(obj).items():
            assert np.allclose(sphere[vertex], locations[name], atol=1e-5), (obj.name, name)
        stats = consistent_maps.results.stats(obj.data)
        assert stats["bijective"] and "steiner_vertices" in stats
    surface = consistent_maps.results.surface(a.data)
    assert surface[0].shape[0] >= len(a.data.vertices) and on_unit_sphere(surface[2])


def test_remesh_operator_creates_consistent_remeshes():
    a, b = _consistent_pair()
    before = [snapshot(a), snapshot(b)]
    bpy.context.scene.consistent_maps.resolution = 16
    assert bpy.ops.consistent_maps.remesh() == {'FINISHED'}
    collection = bpy.data.collections["Consistent Maps"]
    remeshed = [bpy.data.objects["A remesh"], bpy.data.objects["B remesh"]]
    assert all(obj.name in collection.objects for obj in remeshed)
    for obj in remeshed:
        assert len(obj.data.vertices) == 16 * 16 + 2 and len(obj.data.polygons) == 2 * 16 * 16
    polygons = [[tuple(p.vertices) for p in obj.data.polygons] for obj in remeshed]
    assert polygons[0] == polygons[1], "one connectivity"
    assert api.features(remeshed[0]) == api.features(remeshed[1]) and len(api.features(remeshed[0])) == 3
    assert remeshed[1].matrix_world == b.matrix_world
    assert [snapshot(a), snapshot(b)] == before, "originals untouched"
    created = api.remesh([a, b], 8)
    assert [len(obj.data.vertices) for obj in created] == [66, 66]


def test_remesh_errors():
    a = load(BALL, "A")
    make_set([a])
    expect_error(bpy.ops.consistent_maps.remesh, "press Compute")
    bpy.ops.consistent_maps.compute()
    for resolution in (7, 0):
        try:
            api.remesh([a], resolution)
            raise AssertionError("odd or zero resolution must be refused")
        except api.ComputeError as e:
            assert "even" in str(e)
    b = load(BALL, "B")
    api.compute([b], effort=0)  # a later computation: A no longer belongs to the scene's set
    expect_error(bpy.ops.consistent_maps.remesh, "not computed with the set")
    a.data.vertices[0].co.x += 0.1
    try:
        api.remesh([a], 8)
        raise AssertionError("stale results must not be remeshed")
    except api.ComputeError as e:
        assert "no current result" in str(e)
    assert "Consistent Maps" not in bpy.data.collections


# -- error paths: a plain message, nothing modified ----------------------------------------------

def _refused(path, fragment, extra=None):
    bad = load(path, "Bad")
    good = load(BALL, "Good")
    objects = [bad, good] if extra is None else [bad, good, extra]
    for obj in objects:
        with_features(obj, vertices=(0, 1, 2))
    make_set(objects)
    before = [snapshot(obj) for obj in objects]
    message = expect_error(bpy.ops.consistent_maps.compute, fragment)
    assert "'Bad'" in message, message
    assert [snapshot(obj) for obj in objects] == before, "nothing modified"
    return message


def test_error_non_manifold():
    message = _refused(SHARED / "invalid" / "dino_nonmanifold_edges.off", "non-manifold")
    assert "Select All by Trait > Non Manifold" in message
    assert status.of(bpy.data.objects["Bad"]).manifold is False


def test_error_several_components():
    _refused(SHARED / "invalid" / "teapot_newell_nonmanifold.obj", "components")


def test_error_higher_genus():
    _refused(SHARED / "higher-genus" / "torus.obj", "genus 1")
    assert status.of(bpy.data.objects["Bad"]).genus == 1


def test_error_open_mesh():
    _refused(SHARED / "boundary" / "face_disk.off", "boundary")


def test_error_missing_and_unplaced_features():
    a, b = with_features(load(BALL, "A")), load(BALL, "B")
    api.add_feature(b, "tip", 0)
    b.vertex_groups.new(name="CM:left")
    make_set([a, b])
    before = [snapshot(a), snapshot(b)]
    message = expect_error(bpy.ops.consistent_maps.compute, "'right' placed only on 'A'")
    assert "'left' is not placed on 'B'" in message and "at least 3" in message
    assert [snapshot(a), snapshot(b)] == before


def test_error_empty_set_and_loose_vertex():
    expect_error(bpy.ops.consistent_maps.compute, "set is empty")
    a = load(BALL, "A")
    a.data.vertices.add(1)
    make_set([a])
    expect_error(bpy.ops.consistent_maps.compute, "unreferenced vertex")


def test_compute_leaves_edit_mode_first():
    a = load(BALL, "A")
    make_set([a])
    edit_select_vertices(a, {0})
    assert bpy.ops.consistent_maps.compute() == {'FINISHED'}
    assert a.mode == 'OBJECT' and api.result_state(a) == "CURRENT"
    edit_select_vertices(a, {0})
    try:
        api.compute([a])
        raise AssertionError("the API refuses objects in Edit Mode")
    except api.ComputeError as e:
        assert "Edit Mode" in str(e)
    bpy.ops.object.mode_set(mode='OBJECT')


# -- visual check -------------------------------------------------------------------------------

def _colour_by_position(obj):
    """A point colour attribute from the original positions, so the sphere shows where each part went."""
    co = np.array([list(v.co) for v in obj.data.vertices])
    rgb = (co - co.min(axis=0)) / (co.max(axis=0) - co.min(axis=0))
    rgba = np.hstack([rgb, np.ones((len(rgb), 1))]).astype(np.float32)
    obj.data.attributes.new("where", 'FLOAT_COLOR', 'POINT').data.foreach_set("color", rgba.ravel())
    obj.data.attributes.active_color = obj.data.attributes["where"]


def _marker(position, rgba, name):
    """A small ball at a feature, in the feature's overlay colour (the overlay itself is not rendered)."""
    bm = bmesh.new()
    bmesh.ops.create_icosphere(bm, subdivisions=2, radius=0.05)
    mesh = bpy.data.meshes.new(f"marker {name}")
    bm.to_mesh(mesh)
    bm.free()
    mesh.attributes.new("where", 'FLOAT_COLOR', 'POINT').data.foreach_set("color", list(rgba) * len(mesh.vertices))
    mesh.attributes.active_color = mesh.attributes["where"]
    obj = bpy.data.objects.new(f"marker {name}", mesh)
    obj.location = position
    bpy.context.scene.collection.objects.link(obj)


def _place(objects):
    """Side by side along x, facing the camera of _render."""
    for i, obj in enumerate(objects):
        obj.location = (1.1 * (2 * i - len(objects) + 1), 0, 0)
        obj.rotation_euler = (np.pi / 2, 0, -3 * np.pi / 4)  # Spot's OBJ is y-up
    bpy.context.view_layer.update()


def _render(name):
    """Workbench render (objects coloured by their colour attribute): out/blender/<name>-<version>.png."""
    scene = bpy.context.scene
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(camera)
    camera.data.type = 'ORTHO'
    camera.data.ortho_scale = 4.4
    camera.location = (0, -5, 0.1)
    camera.rotation_euler = (np.pi / 2, 0, 0)
    scene.camera = camera
    scene.render.engine = 'BLENDER_WORKBENCH'
    scene.display.shading.light = 'STUDIO'
    scene.display.shading.color_type = 'VERTEX'
    scene.render.resolution_x, scene.render.resolution_y = 640, 320
    OUT.mkdir(parents=True, exist_ok=True)
    scene.render.filepath = str(OUT / f"{name}-{VERSION}.png")
    bpy.ops.render.render(write_still=True)
    assert os.path.getsize(scene.render.filepath) > 5000


def test_render_remeshes():
    """Consistent remeshes of Spot (low) and Spot (finer mesh, features at the nearest vertices),
    coloured by vertex index: identical colours mean corresponding points. out/blender/remeshes-*.png."""
    low = load(SPOT, "Spot low")
    fine = load(SHARED / "genus0" / "spot.obj", "Spot")
    fine_co = np.array([list(v.co) for v in fine.data.vertices])
    for name, index in (("a", 0), ("b", 100), ("c", 200), ("d", 400), ("e", 600)):
        api.add_feature(low, name, index)
        nearest = int(np.argmin(np.linalg.norm(fine_co - np.array(low.data.vertices[index].co), axis=1)))
        api.add_feature(fine, name, nearest)
    api.compute([low, fine], effort=0)
    remeshed = api.remesh([low, fine], 32)
    _colour_by_position(remeshed[0])
    colours = remeshed[0].data.attributes["where"]
    rgba = np.empty(len(colours.data) * 4, dtype=np.float32)
    colours.data.foreach_get("color", rgba)
    remeshed[1].data.attributes.new("where", 'FLOAT_COLOR', 'POINT').data.foreach_set("color", rgba)
    remeshed[1].data.attributes.active_color = remeshed[1].data.attributes["where"]
    for obj in (low, fine):
        obj.hide_render = True
    _place(remeshed)
    _render("remeshes")


def test_render_sphere_preview():
    """Workbench render of Spot next to its sphere preview, both coloured by the original position,
    features as balls in their overlay colours: out/blender/sphere_preview-<version>.png."""
    spot = with_features(load(SPOT, "Spot"))
    ball = with_features(load(SPOT, "Spot sphere"))
    for obj in (spot, ball):
        _colour_by_position(obj)
    _place([spot, ball])
    make_set([spot, ball])
    api.compute([spot, ball], effort=0)
    api.show_sphere(ball)
    bpy.context.view_layer.update()
    for point in overlay.feature_points(bpy.context):
        _marker(*point)
    _render("sphere_preview")
