"""Consistent remeshes of pairs mapped directly (`remesh_pair`, `cmaps intersurface --remesh N`): per pair and
resolution, which mesh carried, the remesh's folded triangles against the map's folded samples, how far each
original's vertices lie from its remesh, and the time. Writes the `pair-remesh-benchmark` section of
BENCHMARKS.md.

    python3 bench/pair_remesh_benchmark.py
"""
import json
import sys
import time

import numpy as np

from bench_common import MESHES, ROOT, diagonal, farthest_points, machine, write_section

sys.path.insert(0, str(ROOT / "addon"))
from consistent_maps import _native  # noqa: E402

RESOLUTIONS = (16, 32, 64)


def animal_pairs():
    names = json.loads((ROOT / "bench" / "features" / "animals.json").read_text())
    return [[v[1], v[0]] for v in names.values() if v[0] is not None and v[1] is not None]  # cow, horse


def cactus_pairs():
    rest = _native.read_mesh(str(MESHES / "sets" / "cactus" / "cactus0.ply"))[0]
    return [[v, v] for v in farthest_points(rest, 8)]


PAIRS = [
    ("examples/meshes/kitten.off", "examples/meshes/torus.obj", "none", lambda: []),
    ("higher-genus/torus.obj", "higher-genus/knot.obj", "1 ([0, 7])", lambda: [[0, 7]]),
    ("sets/cactus/cactus0.ply", "sets/cactus/cactus1.ply", "8 (farthest points)", cactus_pairs),
    ("genus0/cow.off", "large/horse.ply", "19 (bench/features/animals.json)", animal_pairs),
]


def mesh(path):
    return _native.read_mesh(str(ROOT / path if path.startswith("examples/") else MESHES / path))


def distance(original, points, triangles):
    """Mean and largest distance of the original's vertices from the remesh, in % of its diagonal."""
    found = _native.SurfaceLocator(points, triangles).locate(original[0])[2]
    return 100 * found.mean() / diagonal(original[0]), 100 * found.max() / diagonal(original[0])


def main():
    lines = [f"Measured {machine()} (machine shared with other work); the map by `intersurface_map` (Python, effort "
             "1, 2 threads, the pair's features), then `remesh_pair` at N^2 + 2 vertices. Folded: remesh triangles "
             "facing against the surface they lie on (either remesh), against the map's folded samples A->B / B->A "
             "(its vertex sampling at full resolution). Distance: each original's vertices from its remesh, mean / "
             "largest, % of its diagonal. Truth (cactus, shared vertex order): the images' mean distance from the "
             "true positions, % of the diagonal.", "",
             "| pair | features | N | vertices (carrier) | folded / triangles | map's folded samples | "
             "distance A | distance B | truth | remesh s |", "|---|---|---|---|---|---|---|---|---|---|"]
    for name_a, name_b, described, pairs in PAIRS:
        a, b = mesh(name_a), mesh(name_b)
        features = pairs()
        r = _native.intersurface_map(a, b, features, threads=2)
        a_to_b = (r["a_to_b_triangle"], r["a_to_b_barycentric"])
        b_to_a = (r["b_to_a_triangle"], r["b_to_a_barycentric"])
        for n in RESOLUTIONS:
            start = time.perf_counter()
            remesh = _native.remesh_pair(a, b, a_to_b, b_to_a, features, n * n + 2)
            seconds = time.perf_counter() - start
            near_a = distance(a, remesh["a_positions"], remesh["triangles"])
            near_b = distance(b, remesh["b_positions"], remesh["triangles"])
            truth = "n/a"
            if "cactus" in name_a:  # shared vertex order: the carrier's vertex is its own truth on the other pose
                other, images = (a, remesh["a_positions"]) if remesh["b_carries"] else (b, remesh["b_positions"])
                error = np.linalg.norm(images - other[0][remesh["carrier_vertex"]], axis=1).mean()
                truth = f"{100 * error / diagonal(other[0]):.2f} %"
            carrier = "B" if remesh["b_carries"] else "A"
            lines.append(f"| {name_a} - {name_b} | {described} | {n} | {len(remesh['carrier_vertex']):,} ({carrier}) | "
                         f"{remesh['folded_triangles']} / {len(remesh['triangles']):,} | "
                         f"{r['flipped'][0]:,} / {r['flipped'][1]:,} | {near_a[0]:.3f} / {near_a[1]:.2f} % | "
                         f"{near_b[0]:.3f} / {near_b[1]:.2f} % | {truth} | {seconds:.2f} |")
            print(lines[-1], flush=True)
    write_section("pair-remesh-benchmark", lines)


if __name__ == "__main__":
    main()
