"""Inter-surface maps of genus >= 1 (issue 5): `cmaps intersurface` on pairs of equal genus from
shared/meshes/higher-genus, plus the torus, genus3 and fertility (genus 4) against stretched, re-indexed
copies of themselves, where the true correspondence is known. Rewrites the `intersurface-genus-benchmark`
section of BENCHMARKS.md.

    python3 bench/intersurface_benchmark.py   (after building build/cmaps)
"""
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_common import MESHES, farthest_points, machine, run_cmaps, write_section

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "addon"))
from consistent_maps import _native  # noqa: E402

HIGHER = MESHES / "higher-genus"


def axis_extremes(path):
    """Four vertices of a mesh: lowest and highest along x, then along y (a deterministic rule, not semantic)."""
    vertices = _native.read_mesh(str(path))[0]
    return [int(vertices[:, 0].argmin()), int(vertices[:, 0].argmax()), int(vertices[:, 1].argmin()),
            int(vertices[:, 1].argmax())]


def write_features(directory, pairs):
    path = Path(directory) / "features.json"
    path.write_text(json.dumps({f"f{k}": [a, b] for k, (a, b) in enumerate(pairs)}))
    return str(path)


def write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        f.writelines(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in vertices)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles)
    return path


def holed(vertices, triangles, centres):
    """The mesh without the triangles around each of `centres` (and without those vertices)."""
    keep = np.ones(len(vertices), bool)
    keep[list(centres)] = False
    index = np.cumsum(keep) - 1
    return vertices[keep], index[triangles[keep[triangles].all(axis=1)]]


def stretched_copy(directory, name="torus.obj", bend=0.0):
    """A mesh of HIGHER re-indexed and scaled by (1.5, 1, 0.7), then bent (y += bend * x^2 about the centre, x
    over the largest centred coordinate); returns its path, old -> new vertex index and moved positions."""
    vertices, triangles = _native.read_mesh(str(HIGHER / name))
    new_index = np.random.default_rng(1).permutation(len(vertices))
    centred = vertices - vertices.mean(axis=0)
    size = np.abs(centred).max()
    moved = np.empty_like(vertices)
    moved[new_index] = vertices * np.array([1.5, 1.0, 0.7])
    moved[new_index, 1] += bend * size * (centred[:, 0] / size) ** 2
    path = Path(directory) / f"{Path(name).stem}_stretched.obj"
    return write_obj(path, moved, new_index[triangles]), new_index, moved


def truth_rows(tmp, name, label, counts, bend=0.0):
    """Rows of `name` against its stretched copy with 0 or more true pairs (random, seed 5): mean error of A's
    images from the truth."""
    path, new_index, moved = stretched_copy(tmp, name, bend)
    diagonal = np.linalg.norm(moved.max(axis=0) - moved.min(axis=0))
    rows = []
    for k in counts:
        chosen = np.random.default_rng(5).choice(len(new_index), k, replace=False)
        arguments = ["--features", write_features(tmp, [(int(v), int(new_index[v])) for v in chosen])] if k else []
        result = run_cmaps("intersurface", str(HIGHER / name), str(path), *arguments, "-o", tmp + "/out")
        if result.get("error"):
            error = "failed"
        else:
            on_b = obj_positions(tmp + "/out/A_on_B.obj")
            error = f"{100 * np.linalg.norm(on_b - moved[new_index], axis=1).mean() / diagonal:.1f} %"
        rows.append(row(label, result, f" {k} true pairs; mean error {error} of the diagonal"))
        print(rows[-1], flush=True)
    return rows


def obj_positions(path):
    return np.array([l.split()[1:4] for l in open(path) if l.startswith("v ")], float)


def row(name, result, note=""):
    if result.get("error"):
        return f"| {name} | {result['faces'][0]} / {result['faces'][1]} | | failed: {result['error']} ||||||||||{note} |"
    given = result["features"]
    added = len(result["added_features"])
    balance = f"{result['patch_area_ratio']:.2f}" + (" (balanced)" if result["balanced_patches"] else "")
    median = result["median_symmetric_dirichlet"]
    return (f"| {name} | {result['faces'][0]} / {result['faces'][1]} | {given} (+{added} listed, "
            f"{result['base_vertices']} base vertices) | {result['base_triangles']} | "
            f"{result['steiner'][0]} / {result['steiner'][1]} | {result['seconds_partition']:.2f} | "
            f"{result['seconds_parameterize'] + result['seconds_optimize'] + result['seconds_locate']:.2f} "
            f"({result['seconds_optimize']:.2f} opt.) | {result['wall']:.1f} | "
            f"{result['symmetric_dirichlet'][0]:.1f} / {result['symmetric_dirichlet'][1]:.1f} | "
            f"{median[0]:.1f} / {median[1]:.1f} | {result['flipped'][0]} / {result['flipped'][1]} | "
            f"{result['map_flipped']} | {balance} |{note} |")


def screened_note(result):
    return (f" {len(result['start_median_dirichlet'])} first pairs screened (patch areas matched, no sweeps), "
            "summed medians " + " / ".join(f"{m:.1f}" for m in result["start_median_dirichlet"]))


def main():
    lines = [f"Measured {machine()} (machine shared with other work); `cmaps intersurface A B [--features FILE] "
             "-o DIR --json`. Base vertices: all vertices of the base triangulation (given + added pairs; added "
             "pairs that are Steiner vertices are not listed in `features`). Map seconds: patch "
             "parameterization + local optimization + point location. Symmetric Dirichlet: area-weighted mean over the "
             "source's triangles (what the command reports; a few near-degenerate sampled image triangles dominate "
             "it) and the median triangle's (as the command reports it, the other surface scaled to the source's area; "
             "optimum 4). Patch area ratio: the "
             "largest ratio of a patch's shares of A's and B's area in the partition used, \"balanced\" when the map "
             "through the partition with balanced patch areas was kept (partition s includes the balancing, map s "
             "both maps; after screening, the one the screened map kept). Map folds: the map's own (`map_flipped`: "
             "A's and B's triangles turned over in their patches' embeddings, B's vertices outside their host "
             "triangle of A; 0: bijective as computed), unlike the flipped samples, folds of the vertex sampling.",
             "",
             "| pair | faces | features | base triangles | Steiner A / B | partition s | map s | total s | "
             "symmetric Dirichlet A->B / B->A | median | flipped samples A->B / B->A | map folds | patch area ratio | "
             "note |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    pairs = [("torus", "knot"), ("eight", "skull"), ("kitten", "rocker-arm"), ("kitten", "elk"),
             ("cup", "skull")]
    files = {p.stem: p for p in HIGHER.iterdir()}
    with tempfile.TemporaryDirectory() as tmp:
        for starts in (1, None):
            for a, b in pairs:
                arguments = ["--starts", str(starts)] if starts else []
                result = run_cmaps("intersurface", str(files[a]), str(files[b]), "-o", tmp + "/out", *arguments)
                note = " `--starts 1`: the first pair only" if starts else screened_note(result)
                lines.append(row(f"{a} - {b}", result, note))
                print(lines[-1], flush=True)
        # The largest pair of equal genus the shared meshes offer (165k faces), without features.
        result = run_cmaps("intersurface", str(files["feline"]), str(files["teapot"]), "-o", tmp + "/out")
        lines.append(row("feline - teapot", result, screened_note(result)))
        print(lines[-1], flush=True)
        for a, b in [("feline", "cup"), ("feline", "skull")]:
            features = write_features(tmp, zip(axis_extremes(files[a]), axis_extremes(files[b])))
            result = run_cmaps("intersurface", str(files[a]), str(files[b]), "--features", features, "-o",
                               tmp + "/out")
            lines.append(row(f"{a} - {b}", result, " 4 axis-extreme pairs"))
            print(lines[-1], flush=True)
        # Ground truth: a mesh against its stretched (genus 3 and 4: also bent), re-indexed copy.
        lines += truth_rows(tmp, "torus.obj", "torus - stretched copy", (0, 8, 16))
        lines += truth_rows(tmp, "genus3.off", "genus3 - stretched, bent copy", (0, 12), bend=0.3)
        lines += truth_rows(tmp, "fertility.off", "fertility - stretched, bent copy", (0, 12), bend=0.3)
        # Holes: two on each mesh (the triangles around two far-apart vertices removed).
        torus, knot = (_native.read_mesh(str(HIGHER / name)) for name in ("torus.obj", "knot.obj"))
        holed_torus = holed(*torus, farthest_points(torus[0], 2))
        path_a = write_obj(Path(tmp) / "torus_holes.obj", *holed_torus)
        path_knot = write_obj(Path(tmp) / "knot_holes.obj", *holed(*knot, farthest_points(knot[0], 2)))
        result = run_cmaps("intersurface", str(path_a), str(path_knot), "-o", tmp + "/out")
        lines.append(row("torus - knot, 2 holes each", result, " 0 pairs (rim pairs added)"))
        print(lines[-1], flush=True)
        vertices, triangles = holed_torus
        new_index = np.random.default_rng(1).permutation(len(vertices))
        moved = np.empty_like(vertices)
        moved[new_index] = vertices * np.array([1.5, 1.0, 0.7])
        path_b = write_obj(Path(tmp) / "torus_holes_stretched.obj", moved, new_index[triangles])
        diagonal = np.linalg.norm(moved.max(axis=0) - moved.min(axis=0))
        chosen = farthest_points(vertices, 16)
        features = write_features(tmp, [(int(v), int(new_index[v])) for v in chosen])
        result = run_cmaps("intersurface", str(path_a), str(path_b), "--features", features, "-o", tmp + "/out")
        error = np.linalg.norm(obj_positions(tmp + "/out/A_on_B.obj") - moved[new_index], axis=1).mean() / diagonal
        lines.append(row("torus - stretched copy, 2 holes each", result,
                         f" 16 true pairs; mean error {100 * error:.1f} % of the diagonal"))
        print(lines[-1], flush=True)
    lines += ["", *guide_sweep()]
    write_section("intersurface-genus-benchmark", lines)


def guide_sweep():
    """The torus against its stretched, re-indexed copy over many sets of true pairs (Python API): how often
    the partition's handles match."""
    vertices, triangles = _native.read_mesh(str(HIGHER / "torus.obj"))
    with tempfile.TemporaryDirectory() as tmp:
        _, new_index, moved = stretched_copy(tmp)
    stretched = (moved, new_index[triangles])
    diagonal = np.linalg.norm(moved.max(axis=0) - moved.min(axis=0))
    sets = [(f"random (seed {s})", np.random.default_rng(s).choice(len(vertices), k, replace=False))
            for s in (5, 6, 7, 8) for k in (4, 6, 8, 12)]
    sets += [("farthest points", np.array(farthest_points(vertices, k), dtype=int)) for k in (0, 6, 8, 12, 16)]
    errors = []
    for _, chosen in sets:
        pairs = np.array([(v, new_index[v]) for v in chosen], dtype=np.int64).reshape(-1, 2)
        result = _native.intersurface_map((vertices, triangles), stretched, pairs)
        errors.append(100 * np.linalg.norm(result["a_on_b"] - moved[new_index], axis=1).mean() / diagonal)
    errors = np.array(errors)
    rows = [f"| {name} | {len(chosen)} | {e:.1f} % |" for (name, chosen), e in zip(sets, errors)]
    return ["Torus against its stretched (1.5, 1, 0.7), re-indexed copy, Python `intersurface_map`, "
            f"{len(sets)} sets of true pairs: mean error {errors.mean():.1f} % of the diagonal, median "
            f"{np.median(errors):.1f} %, worst {errors.max():.1f} %, {(errors < 5).sum()} of {len(sets)} under 5 %.",
            "", "| pairs | count | mean error |", "|---|---|---|", *rows]


if __name__ == "__main__":
    main()
