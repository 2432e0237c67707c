"""Shared helpers of the benchmark scripts: run one `cmaps` command as its own
process (wall time, peak memory) and rewrite one marked section of BENCHMARKS.md."""
import json
import os
import platform
import subprocess
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
MESHES = ROOT.parent / "shared" / "meshes"
CMAPS = ROOT / "build" / "cmaps"
BENCHMARKS = ROOT / "BENCHMARKS.md"


def run_cmaps(*arguments: str) -> dict:
    """Runs `cmaps ARGUMENTS --json`; returns its JSON plus `wall` (s) and `peak_mb` (max RSS)."""
    start = time.perf_counter()
    process = subprocess.Popen([str(CMAPS), *arguments, "--json"], stdout=subprocess.PIPE,
                               stderr=subprocess.DEVNULL, text=True)
    _, _, usage = os.wait4(process.pid, 0)
    result = json.loads(process.stdout.read())
    result["wall"] = time.perf_counter() - start
    result["peak_mb"] = usage.ru_maxrss / 1024
    return result


def farthest_points(vertices, count):
    """Farthest-point sampling from vertex 0: the benchmarks' features on sets with shared vertex order."""
    chosen, distance = [0], np.full(len(vertices), np.inf)
    while len(chosen) < count:
        distance = np.minimum(distance, np.linalg.norm(vertices - vertices[chosen[-1]], axis=1))
        chosen.append(int(np.argmax(distance)))
    return chosen


def diagonal(vertices):
    return float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))


def machine() -> str:
    return f"{time.strftime('%Y-%m-%d')}, {platform.machine()}, {os.cpu_count()} cores"


def write_section(name: str, lines: list) -> None:
    """Replaces the text between the section's markers (appending it if new)."""
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    block = "\n".join([begin, *lines, end])
    text = BENCHMARKS.read_text() if BENCHMARKS.exists() else "# Benchmarks\n"
    if begin in text:
        text = text[: text.index(begin)] + block + text[text.index(end) + len(end):]
    else:
        text += "\n" + block + "\n"
    BENCHMARKS.write_text(text)
