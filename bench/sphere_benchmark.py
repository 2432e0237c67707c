#!/usr/bin/env python3
"""Spherical parameterization benchmark: `cmaps sphere` on the shared meshes
(large/, heads/, genus0/), one process per mesh; writes wall time, peak
memory, stretch efficiency and flips into BENCHMARKS.md.

    python3 bench/sphere_benchmark.py [--effort N] [--only SUBSTRING]
"""
import argparse
import sys
import tempfile

from bench_common import CMAPS, MESHES, machine, run_cmaps, write_section

# Hoppe's SphereParam at default effort on this kind of machine (issue 2).
REFERENCE = {
    "genus0/bunny.off": (9.2, 0.706),
    "genus0/cow.off": (11.9, 0.435),
    "heads/maxplanck.off": (25.0, 0.939),
    "large/dinosaur.off": (46.3, 0.276),
    "large/armadillo.obj": (70.7, 0.420),
    "large/horse.ply": (71.1, 0.396),
    "large/gargoyle.off": (48.3, 0.736),
    "large/venus.off": (44.3, 0.961),
}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--effort", type=int, default=1)
    parser.add_argument("--only", default="", help="run only meshes whose path contains this (no file written)")
    args = parser.parse_args()
    if not CMAPS.exists():
        sys.exit(f"{CMAPS} is missing: build first (bash scripts/test.sh builds it)")

    rows = []
    for folder in ("large", "heads", "genus0"):
        for mesh in sorted((MESHES / folder).iterdir()):
            name = f"{folder}/{mesh.name}"
            if args.only not in name:
                continue
            with tempfile.TemporaryDirectory() as tmp:
                r = run_cmaps("sphere", str(mesh), "-o", f"{tmp}/out.ply", "--effort", str(args.effort))
            if r.get("error"):
                print(f"{name}: error: {r['error']}", file=sys.stderr)
                continue
            ref = REFERENCE.get(name)
            met = ""
            if ref:
                met = "yes" if (r["flipped"] == 0 and r["stretch_efficiency"] >= ref[1] - 0.01
                                and r["wall"] <= ref[0] / 4) else "NO"
            row = (f"| {name} | {r['faces']} | {r['wall']:.2f} | {r['seconds_simplify']:.2f} | {r['peak_mb']:.0f} | "
                   f"{r['stretch_efficiency']:.3f} | {r['flipped']} | "
                   + (f"{ref[0]:.1f} / {ref[1]:.3f} | {met} |" if ref else "– | |"))
            print(row, flush=True)
            rows.append(row)
    if not args.only:
        write_section("sphere-benchmark", [
            f"Measured {machine()}, effort {args.effort}, `cmaps sphere --json`, one process per mesh "
            "(wall = whole process including file I/O; peak = max RSS). Target: reference efficiency "
            "- 0.01, zero flips, at most a quarter of the reference time.",
            "",
            "| mesh | faces | wall s | simplify s | peak MB | efficiency | flips | reference s / eff | target met |",
            "|---|---|---|---|---|---|---|---|---|",
            *rows,
        ])
    return 0


if __name__ == "__main__":
    sys.exit(main())
