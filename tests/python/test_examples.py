"""The meshes the repository ships (examples/meshes) are credited with a permissive licence in
examples/README.md, with the figures the files have, and are unchanged copies of meshes in ../shared."""
import hashlib
import re

from conftest import ROOT, SHARED

import consistent_maps._native as native

MESHES = ROOT / "examples" / "meshes"
PERMISSIVE = re.compile(r"CC0|public domain|CC BY|MIT", re.IGNORECASE)


def credits():
    """Rows of the examples/README.md table: {file name: (vertices, triangles, licence cell)}."""
    rows = {}
    for line in (ROOT / "examples" / "README.md").read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        found = re.fullmatch(r"`meshes/([^`]+)`", cells[0])
        if found and len(cells) == 5:
            rows[found.group(1)] = (int(cells[1]), int(cells[2]), cells[4])
    return rows


def test_every_shipped_mesh_is_credited_with_a_permissive_licence():
    shipped = sorted(p.name for p in MESHES.iterdir() if p.suffix in (".obj", ".off", ".ply", ".stl"))
    rows = credits()
    assert shipped and sorted(rows) == shipped
    for name, (vertices, triangles, licence) in rows.items():
        assert PERMISSIVE.search(licence), (name, licence)
        for notice in re.findall(r"`meshes/([^`]+)`", licence):  # a licence text shipped beside the mesh
            assert (MESHES / notice).is_file(), notice
        read_vertices, read_triangles = native.read_mesh(str(MESHES / name))
        assert (len(read_vertices), len(read_triangles)) == (vertices, triangles), name


def test_shipped_meshes_are_unchanged_copies_of_shared_ones():
    digest = {}
    for path in SHARED.rglob("*"):
        if path.suffix in (".obj", ".off"):
            digest.setdefault(hashlib.sha256(path.read_bytes()).hexdigest(), path)
    for path in MESHES.iterdir():
        if path.suffix in (".obj", ".off"):
            assert hashlib.sha256(path.read_bytes()).hexdigest() in digest, path.name
