#!/usr/bin/env python3
"""Spherical parameterization benchmark: runs `cmaps sphere --json` on the
shared meshes (large/, heads/, genus0/), one process per mesh, and writes wall
time, peak memory (max RSS of that process), stretch efficiency and flips into
BENCHMARKS.md between the markers of the sphere section.

    python3 bench/sphere_benchmark.py [--effort N] [--only SUBSTRING] [--no-write]
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MESHES = ROOT.parent / "shared" / "meshes"
CMAPS = ROOT / "build" / "cmaps"
BENCHMARKS = ROOT / "BENCHMARKS.md"
BEGIN, END = "<!-- sphere-benchmark:begin -->", "<!-- sphere-benchmark:end -->"

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


def run(mesh: Path, effort: int) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        command = [str(CMAPS), "sphere", str(mesh), "-o", f"{tmp}/out.ply", "--json", "--effort", str(effort)]
        start = time.perf_counter()
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - start
        out = process.stdout.read()
        process.returncode = os.waitstatus_to_exitcode(status)
    result = json.loads(out)
    result["wall"] = wall
    result["peak_mb"] = usage.ru_maxrss / 1024
    return result


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--effort", type=int, default=1)
    parser.add_argument("--only", default="")
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args()
    if not CMAPS.exists():
        sys.exit(f"{CMAPS} is missing: build first (bash scripts/test.sh builds it)")

    meshes = [p for folder in ("large", "heads", "genus0") for p in sorted((MESHES / folder).iterdir())]
    rows = []
    for mesh in meshes:
        name = f"{mesh.parent.name}/{mesh.name}"
        if args.only not in name:
            continue
        r = run(mesh, args.effort)
        if "error" in r:
            print(f"{name}: error: {r['error']}", file=sys.stderr)
            continue
        ref = REFERENCE.get(name)
        verdict = ""
        if ref:
            ok = r["flipped"] == 0 and r["stretch_efficiency"] >= ref[1] - 0.01 and r["wall"] <= ref[0] / 4
            verdict = "yes" if ok else "NO"
        row = (f"| {name} | {r['faces']} | {r['wall']:.2f} | {r['seconds_simplify']:.2f} | {r['peak_mb']:.0f} | "
               f"{r['stretch_efficiency']:.3f} | {r['flipped']} | "
               + (f"{ref[0]:.1f} / {ref[1]:.3f} | {verdict} |" if ref else "– | |"))
        print(row, flush=True)
        rows.append(row)

    table = "\n".join([
        BEGIN,
        f"Measured {time.strftime('%Y-%m-%d')} on {platform.machine()}, {os.cpu_count()} cores, "
        f"effort {args.effort}, `cmaps sphere --json`, one process per mesh "
        f"(wall = whole process including file I/O; peak = max RSS).",
        "",
        "| mesh | faces | wall s | of which simplify s | peak MB | efficiency | flips | reference s / eff | target met |",
        "|---|---|---|---|---|---|---|---|---|",
        *rows,
        END,
    ])
    if not args.no_write and not args.only:
        text = BENCHMARKS.read_text() if BENCHMARKS.exists() else ""
        if BEGIN in text:
            text = text[: text.index(BEGIN)] + table + text[text.index(END) + len(END):]
        else:
            text += "\n" + table + "\n"
        BENCHMARKS.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
