"""Inter-surface maps of genus 0 (issue 5): `cmaps intersurface` through the common sphere on the issue's
pairs: sets/cat-lion with its 20 landmarks (agreement with the approximate dense map lion2cat), sets/cactus
pose 0 to poses 1-4 with 8 features (true correspondence: shared vertex order), genus0/cow - large/horse and
genus0/bunny - large/gargoyle with the hand-picked features of bench/features. Rewrites the
`intersurface-sphere-benchmark` section of BENCHMARKS.md.

    python3 bench/intersurface_sphere_benchmark.py   (after building build/cmaps)
"""
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_common import MESHES, ROOT, diagonal, farthest_points, machine, run_cmaps, write_section

sys.path.insert(0, str(ROOT / "addon"))
from consistent_maps import _native  # noqa: E402

CACTUS = MESHES / "sets" / "cactus"
CACTUS_RESTARTS = (1, 3, 6)


def pair_features(directory, file, a, b):
    """Columns a and b of a set's feature file, as intersurface pairs (features one of them lacks dropped)."""
    names = json.loads((ROOT / "bench" / "features" / file).read_text())
    pairs = {name: [v[a], v[b]] for name, v in names.items() if v[a] is not None and v[b] is not None}
    path = Path(directory) / f"{file}.{a}.{b}.json"
    path.write_text(json.dumps(pairs))
    return str(path), len(pairs)


def landmark_error(out, target, file, a, b):
    """How far the hand-picked features of a pair mapped without them land from their partners: mean and worst
    distance between A's feature's image and B's, % of B's bounding-box diagonal."""
    names = json.loads((ROOT / "bench" / "features" / file).read_text())
    images, partners = read_obj_vertices(out + "/A_on_B.obj"), _native.read_mesh(str(target))[0]
    error = np.array([np.linalg.norm(images[v[a]] - partners[v[b]]) for v in names.values()
                      if v[a] is not None and v[b] is not None]) / diagonal(partners)
    return f"features off by {100 * error.mean():.1f} % (worst {100 * error.max():.0f} %)"


def read_obj_vertices(path):
    return np.array([line.split()[1:4] for line in open(path) if line.startswith("v ")], float)


def row(name, result, features, truth="", restarts=1):
    d, m, c = result["symmetric_dirichlet"], result["median_symmetric_dirichlet"], result["composition_dirichlet"]
    medians = " / ".join("-" if result[f"{k}_median_dirichlet"] is None else f"{result[f'{k}_median_dirichlet']:.2f}"
                         for k in ("sphere", "partition"))
    return (f"| {name} | {result['faces'][0]} / {result['faces'][1]} | {features} | {result['method']} ({medians}) | "
            f"{restarts} | {result['wall']:.1f} ({result['seconds_parameterize']:.1f} / "
            f"{result['seconds_optimize']:.1f}) | {result['peak_mb']:.0f} | {d[0]:.1f} / {d[1]:.1f} | "
            f"{m[0]:.2f} / {m[1]:.2f} | "
            f"{c[0]:.1f} / {c[1]:.1f} | {result['flipped'][0]} / {result['flipped'][1]} | "
            f"{result['map_flipped']} | {truth} |")


def main():
    lines = [f"Measured {machine()} (machine shared with other work), `cmaps intersurface A B --features FILE -o DIR "
             "--json [--restarts K]`, effort 1, default `--optimize 2`. Seconds: wall time of the whole command "
             "(parameterize / optimize, summed over restarts and both maps). `--method auto`: the map through the "
             "common sphere (restarts) and the direct map through a consistent partition, the less distorted kept "
             "(lower summed median; within 5 %: fewer flipped samples, by over 0.5 % of the triangles, else the "
             "direct map). Symmetric Dirichlet by vertex sampling (each source "
             "triangle onto the triangle its corners' images form, target scaled to the source's area; optimum 4): "
             "area-weighted mean and the median triangle's (restarts keep the least distorted likewise); "
             "\"plain\": the composition before refitting and optimization (of the kept restart; for the direct map "
             "its final "
             "distortion). Ground truth: mean "
             "distance between a vertex's image and its true partner, % of the target's bounding-box diagonal "
             "(target < 2 %); without features, how far the hand-picked ones' images land from their partners. "
             "Map folds: the map's own (`map_flipped`; through the sphere, triangles of the two "
             "spherical maps flipped on the sphere; directly, triangles turned over in the patches' embeddings and "
             "vertices of B outside their host triangle of A); 0: bijective as computed, whatever the vertex "
             "sampling's flipped samples.", "",
             "| pair | faces | features | map kept (summed medians sphere / direct) | restarts | seconds (parameterize "
             "/ optimize) | peak MB | symmetric Dirichlet A->B / B->A | median | plain | flipped samples | map folds | "
             "ground truth A->B / B->A |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def emit(line):
        lines.append(line)
        print(line, flush=True)

    with tempfile.TemporaryDirectory() as tmp:
        out = tmp + "/out"
        cat_lion = MESHES / "sets" / "cat-lion"
        landmarks = np.loadtxt(cat_lion / "landmarks.txt", dtype=np.int64)
        features = Path(tmp) / "landmarks.json"
        features.write_text(json.dumps({f"l{k}": [int(a), int(b)] for k, (a, b) in enumerate(landmarks)}))
        result = run_cmaps("intersurface", str(cat_lion / "cat-00.off"), str(cat_lion / "lion-00.off"),
                           "--features", str(features), "-o", out)
        cat = _native.read_mesh(str(cat_lion / "cat-00.off"))[0]
        lion2cat = np.loadtxt(cat_lion / "lion2cat", dtype=np.int64)
        error = np.linalg.norm(read_obj_vertices(out + "/B_on_A.obj") - cat[lion2cat], axis=1).mean() / diagonal(cat)
        emit(row("sets/cat-lion", result, "20 landmarks", f"lion -> cat vs lion2cat: {100 * error:.1f} %"))

        rest = _native.read_mesh(str(CACTUS / "cactus0.ply"))[0]
        chosen = farthest_points(rest, 8)
        features = Path(tmp) / "cactus.json"
        features.write_text(json.dumps({f"f{k}": [v, v] for k, v in enumerate(chosen)}))
        for pose in range(1, 5):
            other = _native.read_mesh(str(CACTUS / f"cactus{pose}.ply"))[0]
            for restarts in CACTUS_RESTARTS:
                result = run_cmaps("intersurface", str(CACTUS / "cactus0.ply"), str(CACTUS / f"cactus{pose}.ply"),
                                   "--features", str(features), "-o", out, "--restarts", str(restarts))
                forward = (np.linalg.norm(read_obj_vertices(out + "/A_on_B.obj") - other, axis=1).mean()
                           / diagonal(other))
                backward = np.linalg.norm(read_obj_vertices(out + "/B_on_A.obj") - rest, axis=1).mean() / diagonal(rest)
                emit(row(f"sets/cactus 0 - {pose}", result, "8 (farthest points)", restarts=restarts, truth=
                         f"{100 * forward:.1f} % / {100 * backward:.1f} %"))

        for a, b, file, (column_a, column_b) in [
                ("genus0/cow.off", "large/horse.ply", "animals.json", (1, 0)),
                ("genus0/bunny.off", "large/gargoyle.off", "bunny_gargoyle.json", (0, 1))]:
            features, count = pair_features(tmp, file, column_a, column_b)
            result = run_cmaps("intersurface", str(MESHES / a), str(MESHES / b), "--features", features, "-o", out)
            emit(row(f"{a} - {b}", result, f"{count} (bench/features/{file})", "n/a"))
            result = run_cmaps("intersurface", str(MESHES / a), str(MESHES / b), "-o", out)
            emit(row(f"{a} - {b}", result, "0 (4 added)",
                     truth=landmark_error(out, MESHES / b, file, column_a, column_b)))
    write_section("intersurface-sphere-benchmark", lines)


if __name__ == "__main__":
    main()
