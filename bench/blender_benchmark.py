"""Add-on benchmark, run inside Blender (`blender -b --factory-startup --python-exit-code 1 -P
bench/blender_benchmark.py`): import time of the package, Compute (synchronous path) on the
example set (spot_low + spot with the ten features of examples/spot_set_features.json) and a morph
between them; then Compute and a morph for two heads under 30k faces (heads/egea.off 8.3k
vertices, heads/mannequin.off 11.7k) with ten features at the extremes. Prints a table row."""
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "addon"))

start = time.perf_counter()
import consistent_maps  # noqa: E402
import_seconds = time.perf_counter() - start

import bpy  # noqa: E402
from consistent_maps import _native, api  # noqa: E402


def load(path):
    vertices, triangles = _native.read_mesh(str(path))
    mesh = bpy.data.meshes.new(path.stem)
    mesh.from_pydata(vertices.tolist(), [], triangles.tolist())
    mesh.update()
    obj = bpy.data.objects.new(path.stem, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def timed(function, *args, **kwargs):
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - start


bpy.ops.wm.read_homefile(use_empty=True)
features = json.loads((ROOT / "examples" / "spot_set_features.json").read_text())
objects = [load(ROOT / "examples" / "meshes" / f"{name}.obj") for name in ("spot_low", "spot")]
for name, (low, high) in features.items():
    api.add_feature(objects[0], name, low)
    api.add_feature(objects[1], name, high)
_, compute_seconds = timed(api.compute, objects)
_, morph_seconds = timed(api.morph, objects[1], objects[0])

heads = ROOT.parent / "shared" / "meshes" / "heads"
pair = [load(heads / "egea.off"), load(heads / "mannequin.off")]
for obj in pair:
    vertices = [v.co for v in obj.data.vertices]
    # Ten features at the extremes along the axes and diagonals (corresponding on both heads).
    for i, d in enumerate([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1),
                           (1, 1, 1), (-1, 1, 1), (1, -1, 1), (-1, -1, 1)]):
        best = max(range(len(vertices)), key=lambda k: sum(a * b for a, b in zip(vertices[k], d)))
        api.add_feature(obj, f"f{i}", best)
_, heads_compute = timed(api.compute, pair)
_, heads_morph = timed(api.morph, pair[1], pair[0])

print(f"| {bpy.app.version_string} | {import_seconds:.2f} | {compute_seconds:.2f} | {morph_seconds:.3f} | "
      f"{len(pair[1].data.vertices)} -> {len(pair[0].data.vertices)} | {heads_compute:.2f} | {heads_morph:.3f} |")
