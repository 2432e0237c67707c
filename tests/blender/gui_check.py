"""The interactive path, in Blender with a window (run under Xvfb by run.sh when xvfb-run exists).

Builds a set of two Spots with features, presses Compute as a user would (modal
operator, worker thread), takes screenshots while it runs and when done, shows
the map's distortion (Show Distortion: the viewport turns to the colour
attribute), then the sphere preview. Screenshots go to out/blender/gui-*.png for
review; exits 1 if the modal run does not finish with both results up to date or
Show Distortion fails (draw errors are caught by run.sh, which fails on any
Python traceback).

    xvfb-run -a -s "-screen 0 1300x1300x24" blender --factory-startup <empty.blend> -P tests/blender/gui_check.py
"""
import os
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "addon"))

import bpy  # noqa: E402

import consistent_maps  # noqa: E402
from consistent_maps import _native, api, job, panels  # noqa: E402

OUT = ROOT / "out" / "blender"
MESH = ROOT.parent / "shared" / "meshes" / "genus0" / "spot.obj"
VERSION = ".".join(map(str, bpy.app.version))
seen = []


def load(name, x):
    vertices, triangles = _native.read_mesh(str(MESH))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices.tolist(), [], triangles.tolist())
    obj = bpy.data.objects.new(name, mesh)
    obj.location.x, obj.rotation_euler.x = x, 1.5708
    bpy.context.scene.collection.objects.link(obj)
    for feature, index in (("nose", 0), ("tail", 1000), ("ear", 2000)):
        api.add_feature(obj, feature, index)
    return obj


def show_panels_in_reach(area):
    """Open the sidebar on the add-on's tab (3.4 cannot switch tabs from Python: move the panels to the
    Tool tab, the one a new window shows, above its own panels)."""
    area.spaces.active.show_region_ui = True
    sidebar = next(r for r in area.regions if r.type == 'UI')
    if hasattr(sidebar, "active_panel_category"):
        sidebar.active_panel_category = panels.CATEGORY
        return
    for cls in reversed(panels.CLASSES):
        bpy.utils.unregister_class(cls)
    for cls in panels.CLASSES:
        if hasattr(cls, "bl_category"):
            cls.bl_category, cls.bl_order = "Tool", -1
        bpy.utils.register_class(cls)


def finish(ok, message):
    print(("GUI CHECK OK: " if ok else "GUI CHECK FAILED: ") + message, flush=True)
    consistent_maps.unregister()
    os._exit(0 if ok else 1)


consistent_maps.register()
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
a, b = load("SpotA", -1), load("SpotB", 1)
window = bpy.context.window_manager.windows[0]
area = next(a for a in window.screen.areas if a.type == 'VIEW_3D')
region = next(r for r in area.regions if r.type == 'WINDOW')
show_panels_in_reach(area)
OUT.mkdir(parents=True, exist_ok=True)


def context():
    return bpy.context.temp_override(window=window, screen=window.screen, area=area, region=region)


def screenshot(name):
    with context():
        bpy.ops.screen.screenshot(filepath=str(OUT / f"gui-{name}-{VERSION}.png"))


def start():
    bpy.context.view_layer.update()
    for obj in (a, b):
        obj.select_set(True)
    bpy.context.view_layer.objects.active = a
    bpy.context.scene.consistent_maps.effort = '2'
    with context():
        bpy.ops.consistent_maps.add_selected()
        bpy.ops.view3d.view_all()
        result = bpy.ops.consistent_maps.compute('INVOKE_DEFAULT')
    if result != {'RUNNING_MODAL'}:
        finish(False, f"Compute returned {result}")


def watch():
    running = job.current()
    if running is not None:
        if running.fraction > 0.3 and "running" not in seen:
            seen.append("running")
            screenshot("running")
        return 0.05
    if api.result_state(a) != "CURRENT" or api.result_state(b) != "CURRENT":
        finish(False, f"results after the modal run: {api.result_state(a)}, {api.result_state(b)}")
    screenshot("done")
    bpy.context.scene.consistent_maps.transfer_source = b
    with context():
        result = bpy.ops.consistent_maps.show_distortion()
    if result != {'FINISHED'} or area.spaces.active.shading.color_type != 'VERTEX':
        finish(False, f"Show Distortion returned {result}, the viewport shows {area.spaces.active.shading.color_type}")
    bpy.app.timers.register(lambda: screenshot("distortion") or preview(), first_interval=0.5)
    return None


def preview():
    with context():
        bpy.ops.consistent_maps.sphere_preview(show=True)
    bpy.app.timers.register(lambda: screenshot("preview") or finish(True, "modal Compute finished, both results up to date"
                                                                + (", progress captured" if seen else "")),
                            first_interval=0.5)


bpy.app.timers.register(start, first_interval=1.0)
bpy.app.timers.register(watch, first_interval=1.5)
bpy.app.timers.register(lambda: finish(False, "timed out"), first_interval=240)
