"""Where maps of one pair distort, region by region: each triangle of A mapped onto B (the library's
`map_distortion`: symmetric Dirichlet energy, B scaled to A's area, optimum 4), grouped by the feature nearest
along edges, area-weighted mean / median per group, for each map given (the `A_to_B.txt` that
`cmaps intersurface A B --features FILE -o DIR` writes). BENCHMARKS.md's table of where the direct map loses to
the sphere's on cow - horse came from:

    F=$(python3 bench/distortion_by_region.py --pairs animals.json 1 0)     # the cow - horse pairs file
    build/cmaps intersurface ../shared/meshes/genus0/cow.off ../shared/meshes/large/horse.ply --features $F \\
        -o /tmp/sphere --method sphere              (and -o /tmp/direct --method partition)
    python3 bench/distortion_by_region.py genus0/cow.off large/horse.ply animals.json 1 0 /tmp/sphere /tmp/direct
"""
import heapq
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_common import MESHES, ROOT

sys.path.insert(0, str(ROOT / "addon"))
from consistent_maps import _native  # noqa: E402


def pairs(file, a, b):
    """Columns a and b of a set's feature file (bench/features), name -> [vertex of A, vertex of B]."""
    names = json.loads((ROOT / "bench" / "features" / file).read_text())
    return {name: [v[a], v[b]] for name, v in names.items() if v[a] is not None and v[b] is not None}


def nearest_seed(vertices, triangles, seeds):
    """Per vertex, the index in `seeds` of the nearest seed along edges (Dijkstra from all at once)."""
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    neighbours = [[] for _ in vertices]
    for u, w in edges:
        length = float(np.linalg.norm(vertices[u] - vertices[w]))
        neighbours[u].append((w, length))
        neighbours[w].append((u, length))
    label, distance = np.full(len(vertices), -1), np.full(len(vertices), np.inf)
    queue = []
    for k, s in enumerate(seeds):
        label[s], distance[s] = k, 0
        queue.append((0.0, s))
    heapq.heapify(queue)
    while queue:
        d, u = heapq.heappop(queue)
        if d > distance[u]:
            continue
        for w, length in neighbours[u]:
            if d + length < distance[w]:
                distance[w], label[w] = d + length, label[u]
                heapq.heappush(queue, (d + length, w))
    return label


def main():
    if sys.argv[1] == "--pairs":
        path = Path(tempfile.mkdtemp()) / "pairs.json"
        path.write_text(json.dumps(pairs(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))))
        print(path)
        return
    mesh_a, mesh_b, file, column_a, column_b, *maps = sys.argv[1:]
    a, b = _native.read_mesh(str(MESHES / mesh_a)), _native.read_mesh(str(MESHES / mesh_b))
    named = pairs(file, int(column_a), int(column_b))
    group = nearest_seed(a[0], a[1], [v[0] for v in named.values()])[a[1][:, 0]]
    measured = []
    for directory in maps:
        image = np.loadtxt(Path(directory) / "A_to_B.txt")
        measured.append(_native.map_distortion(a, b, (image[:, 0].astype(np.int32), image[:, 1:4])))
    area = measured[0]["area"]
    print(f"| region (share of A) | {' | '.join(Path(d).name for d in maps)} |")
    print("|---|" + "---|" * len(maps))
    for k, name in enumerate(["all", *named]):
        chosen = np.ones(len(group), bool) if name == "all" else group == k - 1
        cells = []
        for d in measured:
            energy = d["symmetric_dirichlet"][chosen]
            finite = np.isfinite(energy)
            mean = np.sum(area[chosen][finite] * energy[finite]) / area[chosen][finite].sum()
            cells.append(f"{mean:.2f} / {np.median(energy[~np.isnan(energy)]):.2f}")
        print(f"| {name} ({100 * area[chosen].sum() / area.sum():.1f} %) | {' | '.join(cells)} |")


if __name__ == "__main__":
    main()
