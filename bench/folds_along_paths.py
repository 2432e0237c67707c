"""Where the direct map's distortion and folds sit against its partition's paths: each kept map of the genus >= 1
benchmark's unfeatured pairs (default settings), its input triangles in three classes from `intersurface_map`'s
'a_along_paths' / 'b_along_paths' (cut by a path, touching one, the rest), per class the median symmetric Dirichlet
energy and the folded samples (the library's `map_distortion`). "first": the side whose vertices crossed the paths
first (the run kept was traced from it), "second": the other, which crossed after it (cross_turns, default 2;
`--cross-turns 1` leaves it as its patches laid it out). Prints BENCHMARKS.md's table (about 4 minutes).

    python3 bench/folds_along_paths.py [--cross-turns T]
"""
import argparse
import sys

import numpy as np

from bench_common import MESHES, ROOT

sys.path.insert(0, str(ROOT / "addon"))
from consistent_maps import _native  # noqa: E402

HIGHER = MESHES / "higher-genus"
PAIRS = [
    ("kitten - torus (the example)", ROOT / "examples/meshes/kitten.off", ROOT / "examples/meshes/torus.obj"),
    ("torus - knot", HIGHER / "torus.obj", HIGHER / "knot.obj"),
    ("eight - skull", HIGHER / "eight.off", HIGHER / "skull.obj"),
    ("cup - skull", HIGHER / "cup.off", HIGHER / "skull.obj"),
    ("kitten - elk", HIGHER / "kitten.off", HIGHER / "elk.off"),
    ("kitten - rocker-arm", HIGHER / "kitten.off", HIGHER / "rocker-arm.obj"),
]
CLASSES = ("cut", "touching", "rest")  # along_paths 2, 1, 0


def classes(source, target, image, along):
    """Share of the triangles per class, median per class, folded samples along paths and in all."""
    per_triangle = _native.map_distortion(source, target, image)
    energy, folded = per_triangle["symmetric_dirichlet"], per_triangle["flipped"].astype(bool)
    masks = [along == 2, along == 1, along == 0]
    share = [100 * m.mean() for m in masks]
    median = [float(np.median(energy[m])) if m.any() else float("nan") for m in masks]
    return share, median, int(folded[along > 0].sum()), int(folded.sum())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cross-turns", type=int, help="default: the library's")
    turns = parser.parse_args().cross_turns
    options = {} if turns is None else {"cross_turns": turns}
    print("| pair, side | triangles cut / touching | median cut / touching / rest | folded samples cut + touching "
          "of all |")
    print("|---|---|---|---|")
    for label, path_a, path_b in PAIRS:
        a, b = _native.read_mesh(str(path_a)), _native.read_mesh(str(path_b))
        result = _native.intersurface_map(a, b, **options)
        sides = [("A", path_a.stem, a, b, (result["a_to_b_triangle"], result["a_to_b_barycentric"]),
                  result["a_along_paths"]),
                 ("B", path_b.stem, b, a, (result["b_to_a_triangle"], result["b_to_a_barycentric"]),
                  result["b_along_paths"])]
        for k, (side, name, source, target, image, along) in enumerate(sides):
            share, median, along_folds, folds = classes(source, target, image, along)
            role = "first" if side == result["moved"] else "second"
            head = f"{label}, {name} {role}" if k == 0 else f"{name} {role}"
            print(f"| {head} | {share[0]:.1f} / {share[1]:.1f} % | {median[0]:.1f} / {median[1]:.1f} / {median[2]:.1f} "
                  f"| {along_folds} of {folds} |", flush=True)


if __name__ == "__main__":
    main()
