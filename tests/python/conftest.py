"""Shared fixtures: repository paths, the built module and CLI, and small bad meshes."""
import os
import pathlib
import re
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "meshes"
CMAPS = pathlib.Path(os.environ.get("CMAPS_BINARY", ROOT / "build" / "cmaps"))  # override: e.g. a sanitizer build
sys.path.insert(0, str(ROOT / "addon"))


def readme_table():
    """Rows of shared/meshes/README.md: {file: {"genus": int|None, "b": int, ...}}."""
    rows = {}
    for line in (SHARED / "README.md").read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 7 and re.search(r"\.(obj|off|ply)$", cells[0]):
            rows[cells[0]] = {
                "V": int(cells[1]),
                "F": int(cells[2]),
                "genus": None if cells[3] == "n/a" else int(cells[3]),
                "b": int(cells[4]),
                "manifold": cells[5] == "yes",
                "comps": int(cells[6]),
            }
    return rows


def rejection_reason(relative):
    """The part of the error message expected for a shared mesh that is not a topological sphere."""
    row = readme_table()[relative]
    if relative.startswith("invalid/"):
        return "components" if row["comps"] > 1 else "non-manifold"
    if row["b"] > 0:
        return f"mesh has {row['b']} boundary loop"
    return f"mesh has genus {row['genus']} (closed, 1 component)"


REJECTED = sorted(
    str(p.relative_to(SHARED))
    for folder in ("invalid", "higher-genus", "boundary")
    for p in (SHARED / folder).iterdir()
)

OCTAHEDRON_OBJ = """v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6
"""

# Generated bad inputs: (file name, content, expected reason).
BAD_FILES = [
    ("empty.obj", "", "file is empty"),
    ("nan.obj", OCTAHEDRON_OBJ.replace("v 0 1 0", "v 0 nan 0"), "vertex 2 has a non-finite coordinate"),
    ("out_of_range.obj", OCTAHEDRON_OBJ + "f 1 2 99\n", "refers to vertex 98 but the mesh has 6 vertices"),
    ("one_triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "mesh has only 1 triangle"),
    ("garbage.ply", "this is not a ply file\n", "cannot read"),
    ("mesh.xyz", "1 2 3\n", "unknown extension"),
]


@pytest.fixture(scope="session")
def native():
    from consistent_maps import _native

    return _native


@pytest.fixture(scope="session")
def cmaps_binary():
    if not CMAPS.exists():
        pytest.fail(f"{CMAPS} is missing: run scripts/setup.sh first")
    return CMAPS


@pytest.fixture
def bad_file(tmp_path, request):
    name, content, reason = request.param
    path = tmp_path / name
    path.write_text(content)
    return path, reason
