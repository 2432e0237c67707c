#!/usr/bin/env python3
"""Consistent parameterization benchmark (issue 4): sets with known
correspondence. For each set: time of the whole six-step pipeline, every
member's final efficiency against its own unconstrained efficiency, and the
ground-truth error — where vertex i of member 0 lands on member j through the
common sphere, against member j's vertex i (shared vertex order), as a
fraction of member j's bounding-box diagonal. cat-lion: 20 landmark pairs and
agreement with the approximate dense map lion2cat. Also the spread of final
efficiencies when each member seeds step 1. Sets without shared vertex order
(issue 4: bunny + gargoyle, four animals, five heads) use the hand-verified
semantic features of bench/features/*.json; for them, every member's final
efficiency against its own. Writes BENCHMARKS.md. With --seeds: the ground-truth
sets under seeds 1-7 and with restarts (section consistent-seeds).

    python3 bench/consistent_benchmark.py [--seeds]
"""
import json
import os
import sys
import time

import numpy as np

from bench_common import MESHES, ROOT, diagonal, farthest_points, machine, write_section

sys.path.insert(0, str(ROOT / "addon"))
from consistent_maps import _native  # noqa: E402


def mapped_onto(member_map, points):
    """Surface positions, on the member whose map this is, of points of the common sphere."""
    _, _, extras = member_map
    locator = _native.SphereLocator(extras["refined_sphere"], extras["triangles"])
    triangles, barycentric = locator.locate(points)
    return locator.interpolate(extras["refined_vertices"], triangles, barycentric)


def run_set(name, meshes, features, first=-1):
    start = time.perf_counter()
    result = _native.consistent_spherical_parameterization(meshes, features, first=first)
    return result, time.perf_counter() - start


def efficiency_rows(name, meshes, result, seconds, ground_truth, free=None):
    if free is None:
        free = [_native.spherical_parameterization(v, t)[1]["efficiency"] for v, t in meshes]
    final = [stats["efficiency"] for _, stats, _ in result["members"]]
    flips = sum(stats["flipped"] for _, stats, _ in result["members"])
    ratio = min(f / u for f, u in zip(final, free))
    return (f"| {name} | {len(meshes)} | {len(result['feature_locations'])} | {seconds:.1f} | "
            f"{min(final):.3f} – {max(final):.3f} | {ratio:.0%} | {flips} | {ground_truth} |")


def shared_order(folder, files, count):
    meshes = [_native.read_mesh(str(MESHES / "sets" / folder / f)) for f in files]
    chosen = farthest_points(meshes[0][0], count)
    return meshes, np.array([chosen] * len(meshes))


def ground_truth_error(meshes, result):
    errors = []
    sphere0 = result["members"][0][0]
    for j in range(1, len(meshes)):
        on_j = mapped_onto(result["members"][j], sphere0)
        errors.append(np.linalg.norm(on_j - meshes[j][0], axis=1).mean() / diagonal(meshes[j][0]))
    return errors


FEATURES = ROOT / "bench" / "features"

# Sets with semantic features (issue 4). The feature files map each name to one vertex index per
# member, in exactly this member order (null where a member lacks the feature); they were picked
# on renders of each mesh and checked on contact renders (see BENCHMARKS.md).
SEMANTIC_SETS = [
    ("bunny + gargoyle", ["genus0/bunny.off", "large/gargoyle.off"], "bunny_gargoyle.json"),
    ("four animals", ["large/horse.ply", "genus0/cow.off", "large/dinosaur.off",
                      "genus0/cat-low-resolution.obj"], "animals.json"),
    ("five heads", ["heads/maxplanck.off", "heads/mannequin.off", "heads/max_small.obj",
                    "heads/egea.off", "heads/nefertiti.obj"], "heads.json"),
]


def semantic_set(files, feature_file):
    """Meshes and the (members, k) feature array, -1 where a member lacks a feature."""
    meshes = [_native.read_mesh(str(MESHES / f)) for f in files]
    named = json.loads((FEATURES / feature_file).read_text())
    features = np.array([[-1 if named[name][m] is None else named[name][m] for name in named]
                         for m in range(len(files))])
    return meshes, features


def semantic_rows(name, files, feature_file, rows, member_rows, spread_rows):
    meshes, features = semantic_set(files, feature_file)
    result, seconds = run_set(name, meshes, features)
    free = [_native.spherical_parameterization(v, t)[1]["efficiency"] for v, t in meshes]
    rows.append(efficiency_rows(name, meshes, result, seconds, "n/a (semantic features)", free))
    print(rows[-1], flush=True)
    for m, (f, (_, stats, _)) in enumerate(zip(files, result["members"])):
        present = int((features[m] >= 0).sum())
        member_rows.append(f"| {name} | {f} | {present}/{features.shape[1]} | {stats['efficiency']:.3f} | "
                           f"{free[m]:.3f} | {stats['efficiency'] / free[m]:.0%} | {stats['flipped']} |")
        print(member_rows[-1], flush=True)
    # Each member that has every feature seeds step 1 in turn (a member lacking features cannot).
    seeds = [m for m in range(len(meshes)) if (features[m] >= 0).all()]
    spread_rows.append(spread_row(name, meshes, features, seeds, f"{len(seeds)} (members {', '.join(map(str, seeds))})"))
    print(spread_rows[-1], flush=True)


def spread_row(name, meshes, features, seeds, runs):
    """The largest change of a member's final efficiency, and the range of the mean, over seeding members."""
    finals = np.array([[stats["efficiency"] for _, stats, _ in run_set(name, meshes, features, first)[0]["members"]]
                       for first in seeds])
    return (f"| {name} | {runs} | {(finals.max(axis=0) - finals.min(axis=0)).max():.3f} | "
            f"{finals.mean(axis=1).min():.3f} – {finals.mean(axis=1).max():.3f} |")


def seeds_main() -> int:
    """Seed sensitivity of the sets with ground truth, and what restarts make of it (section consistent-seeds)."""
    rows = []
    sets = {
        "sets/defsphere (all 10)": shared_order("defsphere", [f"defSphere{i}.ply" for i in range(10)], 10),
        "sets/cactus (all 5)": shared_order("cactus", [f"cactus{i}.ply" for i in range(5)], 8),
    }
    for name, (meshes, features) in sets.items():
        free = [_native.spherical_parameterization(v, t)[1]["efficiency"] for v, t in meshes]
        for label, options in [*((f"seed {s}", {"seed": s}) for s in range(1, 8)),
                               ("4 restarts from seed 1", {"restarts": 4}),
                               ("seed 1, aligned (step 7)", {"align": True})]:
            start = time.perf_counter()
            result = _native.consistent_spherical_parameterization(meshes, features, **options)
            seconds = time.perf_counter() - start
            errors = ground_truth_error(meshes, result)
            ratio = min(stats["efficiency"] / f for (_, stats, _), f in zip(result["members"], free))
            kept = f"seed {1 + result['restart']}" if "restarts" in options else ""
            rows.append(f"| {name} | {label} | {seconds:.1f} | {np.mean(errors):.2%} | {np.max(errors):.2%} | "
                        f"{ratio:.0%} | {result['suitability']:.3f} | {kept} |")
            print(rows[-1], flush=True)
    write_section("consistent-seeds", [
        f"`python3 bench/consistent_benchmark.py --seeds`, measured {machine()}, effort 1, grid 64. The same "
        "features as above; each row one run of the whole pipeline with that seed (it turns the random "
        "base of the unconstrained maps: step 1, the members' own maps that guide the paths, step 5), "
        "or `restarts=4` (seeds 1-4, the run with the highest suitability kept), or `align=True` (step 7: "
        "each member's map refitted towards the seeding member's, here member 0, where that lowers the "
        "distortion between them). "
        "`suitability` = the "
        "mean over members of final efficiency / own quick map's efficiency (what restarts rank by); "
        "`ratio` = worst member's final efficiency / its own unconstrained efficiency (effort 1).",
        "",
        "| set | run | seconds | ground truth mean | worst pair | worst ratio | suitability | kept |",
        "|---|---|---|---|---|---|---|---|",
        *rows,
    ])
    return 0


def main() -> int:
    rows, spread_rows, member_rows = [], [], []
    load = os.getloadavg()[0]
    sets = {
        "sets/defsphere (all 10)": shared_order("defsphere", [f"defSphere{i}.ply" for i in range(10)], 10),
        "sets/cactus (all 5)": shared_order("cactus", [f"cactus{i}.ply" for i in range(5)], 8),
    }
    for name, (meshes, features) in sets.items():
        result, seconds = run_set(name, meshes, features)
        errors = ground_truth_error(meshes, result)
        rows.append(efficiency_rows(name, meshes, result, seconds,
                                    f"mean {np.mean(errors):.2%}, worst {np.max(errors):.2%}"))
        print(rows[-1], flush=True)
        seeds = range(min(len(meshes), 5))
        spread_rows.append(spread_row(name, meshes, features, seeds, str(len(seeds))))
        print(spread_rows[-1], flush=True)

    # cat-lion: real landmarks, approximate dense ground truth.
    folder = MESHES / "sets" / "cat-lion"
    cat, lion = (_native.read_mesh(str(folder / f)) for f in ("cat-00.off", "lion-00.off"))
    landmarks = np.loadtxt(folder / "landmarks.txt", dtype=int)
    lion2cat = np.loadtxt(folder / "lion2cat", dtype=int)
    meshes = [cat, lion]
    result, seconds = run_set("cat-lion", meshes, landmarks.T)
    lion_sphere = result["members"][1][0]
    on_cat = mapped_onto(result["members"][0], lion_sphere)
    dense = np.linalg.norm(on_cat - cat[0][lion2cat], axis=1).mean() / diagonal(cat[0])
    cat_sphere = result["members"][0][0]
    landmark_gap = np.abs(cat_sphere[landmarks[:, 0]] - lion_sphere[landmarks[:, 1]]).max()
    rows.append(efficiency_rows("sets/cat-lion", meshes, result, seconds,
                                f"landmarks apart on the sphere by {landmark_gap:.0e}; vs lion2cat {dense:.2%}"))
    print(rows[-1], flush=True)

    for name, files, feature_file in SEMANTIC_SETS:
        semantic_rows(name, files, feature_file, rows, member_rows, spread_rows)

    write_section("consistent-benchmark", [
        f"Measured {machine()} (load average {load:.1f} at the start: `seconds` is wall time on a shared "
        "machine), effort 1, grid 64, Python API (`consistent_spherical_parameterization`). "
        "Features: farthest-point sampling on member 0, same vertex indices on every member (shared "
        "vertex order); cat-lion: its 20 landmark pairs. `ratio` = worst final efficiency / that member's "
        "own unconstrained efficiency (target >= 85 %). Ground truth target: under 2 %.",
        "",
        "| set | members | features | seconds | final efficiencies | worst ratio | flips | ground truth |",
        "|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        "Choice of the first member (step 1): each of the first members used in turn.",
        "",
        "| set | runs | largest change of a member's efficiency | mean efficiency range |",
        "|---|---|---|---|",
        *spread_rows,
        "",
        "Sets with semantic features (issue 4), member order as in the feature files "
        "(`bench/features/bunny_gargoyle.json`: bunny, gargoyle; `animals.json`: horse, cow, dinosaur, "
        "cat; `heads.json`: maxplanck, mannequin, max_small, egea, nefertiti). The features (13 for the "
        "pair: nose, chin, ear tips, four feet, haunches, tail, back, chest; 20 for the animals: nose, "
        "chin, eyes, ear tips, four feet, shoulders, hips, withers, croup, tail base and tip, belly, "
        "chest; 20 for the heads: nose tip, nostrils, eye corners, mouth corners, chin, nose bridge, "
        "brow, ear tops and lobes, top and back of the head, front and back of the neck) were picked "
        "by hand on orthographic Blender renders of each mesh (a ray through the picked pixel gives the "
        "vertex; tips snapped to the extreme vertex nearby), then checked on renders of every member "
        "with the features marked and on the consistent remeshes side by side. `null` where a member "
        "lacks the part: the horse's tail tip (the model has only a stub), the dinosaur's ears, "
        "egea's ears (under the hair) and neck back, nefertiti's top and back of the head (under the "
        "crown). Only members with every feature can seed step 1, hence the runs of the spread table. "
        "Per member: final efficiency against its own unconstrained efficiency (target >= 85 %).",
        "",
        "| set | member | features | final efficiency | own efficiency | ratio | flips |",
        "|---|---|---|---|---|---|---|",
        *member_rows,
    ])
    return 0


if __name__ == "__main__":
    sys.exit(seeds_main() if sys.argv[1:] == ["--seeds"] else main())
