#!/usr/bin/env python3
"""Constrained spherical parameterization benchmark (issue 3): `cmaps
constrained` with 8, 20 and 40 well-spread features (farthest-point sampling)
and targets taken from the unconstrained map, against `cmaps sphere` on the
same mesh; writes efficiency, flips, Steiner vertices and times into
BENCHMARKS.md.

    python3 bench/constrained_benchmark.py [--only SUBSTRING]
"""
import argparse
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_common import CMAPS, MESHES, ROOT, machine, run_cmaps, write_section

sys.path.insert(0, str(ROOT / "addon"))
from consistent_maps import _native  # noqa: E402

MESH_NAMES = ["genus0/bunny.off", "heads/maxplanck.off", "large/armadillo.obj", "large/horse.ply"]
COUNTS = [8, 20, 40]


def farthest_points(vertices: np.ndarray, count: int) -> list:
    chosen = [0]
    distance = np.full(len(vertices), np.inf)
    while len(chosen) < count:
        distance = np.minimum(distance, np.linalg.norm(vertices - vertices[chosen[-1]], axis=1))
        chosen.append(int(np.argmax(distance)))
    return chosen


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", default="", help="run only meshes whose path contains this (no file written)")
    args = parser.parse_args()
    if not CMAPS.exists():
        sys.exit(f"{CMAPS} is missing: build first (bash scripts/test.sh builds it)")
    rows = []
    for name in MESH_NAMES:
        if args.only not in name:
            continue
        mesh = MESHES / name
        vertices, _ = _native.read_mesh(str(mesh))
        with tempfile.TemporaryDirectory() as tmp:
            free = run_cmaps("sphere", str(mesh), "-o", f"{tmp}/free.ply")
            for count in COUNTS:
                features = Path(tmp) / "features.json"
                features.write_text(json.dumps({f"f{i}": v for i, v in enumerate(farthest_points(vertices, count))}))
                r = run_cmaps("constrained", str(mesh), "--features", str(features), "-o", f"{tmp}/out.ply")
                if r.get("error"):
                    print(f"{name} {count}: error: {r['error']}", file=sys.stderr)
                    continue
                constrained_seconds = r["seconds_paths"] + r["seconds_simplify"] + r["seconds_optimize"]
                ratio = r["stretch_efficiency"] / free["stretch_efficiency"]
                row = (f"| {name} | {r['faces']} | {count} | {free['stretch_efficiency']:.3f} | "
                       f"{r['stretch_efficiency']:.3f} | {ratio:.0%} | {r['flipped']} | {r['max_constraint_error']:.0e} | "
                       f"{r['steiner_vertices']} ({r['steiner_fraction']:.1%}) | {free['seconds']:.2f} | "
                       f"{constrained_seconds:.2f} | {r['wall']:.2f} | {r['peak_mb']:.0f} |")
                print(row, flush=True)
                rows.append(row)
    if not args.only:
        write_section("constrained-benchmark", [
            f"Measured {machine()}, effort 1. Features by farthest-point sampling, targets from the "
            "unconstrained map (`cmaps constrained` without `--targets`). `free s` = `cmaps sphere`; "
            "`constrained s` = paths + constrained simplification + refinement (what the constraints add); "
            "`wall s` = the whole command, which also computes the unconstrained map that supplies the "
            "targets and guides the paths. Targets: efficiency >= 90 % of the free one, constrained s <= "
            "1.5 x free s, 100k faces with 20 features < 15 s.",
            "",
            "| mesh | faces | features | free eff | constrained eff | ratio | flips | max error | Steiner | "
            "free s | constrained s | wall s | peak MB |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
            *rows,
        ])
    return 0


if __name__ == "__main__":
    sys.exit(main())
