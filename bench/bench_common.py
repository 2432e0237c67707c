"""Shared helpers of the benchmark scripts: run one `cmaps` command as its own
process (wall time, peak memory) and rewrite one marked section of BENCHMARKS.md."""
import json
import os
import platform
import subprocess
import time
from pathlib import Path

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
