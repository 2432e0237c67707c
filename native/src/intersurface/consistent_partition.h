// Consistent partitioning of two closed meshes of equal genus g >= 1 into
// triangular patches of identical connectivity (thesis 5.4; Schreiner et al.
// 2004, Kraevoy & Sheffer 2004).
//
// Both meshes carry the same graph: base vertices are feature pairs, base
// edges are corresponding non-crossing paths that meet only at features. The
// cyclic order of paths around every feature is kept equal on both meshes
// (each path is traced on A, then on B through the corresponding sectors at
// its ends), so the faces of the two graphs correspond by their boundary
// walks. Every face is a disk once V - E + W = 2 - 2g (W walks) and, on each
// mesh, every walk bounds its own region; the construction reaches that in
// three phases:
//   1. a spanning tree of the features (Kruskal over pairs ranked by their
//      summed, size-normalized distances on both meshes), avoiding swirls:
//      features at extremities joined first, pairs passing a nearby feature
//      on different sides of A and B delayed, then re-routed (thesis 5.4);
//   2. 2g non-separating paths: while the single region has several boundary
//      walks, a path joining two of them (never separating); otherwise a new
//      feature pair on a non-separating cycle of each mesh (tree-cotree, the
//      shortest cycle found), that cycle laid as two paths through a second
//      new pair and joined to the network;
//   3. completion to triangles: a new feature pair in each face whose walk
//      is not three distinct features (the interior vertex farthest from the
//      face's boundary on each mesh), with paths to every corner of the walk
//      in order, inside the face (a disk, so the order is the same on both).
// Paths run over mesh vertices and, where a corridor is thinner than an
// edge, edge midpoints (Steiner vertices). The result is checked (equal
// rotation systems, every face a disk with three distinct corners, Euler
// characteristic 2 - 2g); anything else throws.
#pragma once
#include <array>
#include <vector>

#include "consistent_maps/mesh.h"
#include "intersurface/hole_rims.h"
#include "paths/editable_mesh.h"

namespace cmaps {

// One mesh of the partition, refined by its Steiner vertices.
struct PartitionSide {
  EditableMesh mesh;
  int input_triangles = 0;               // refined from input triangles at or past this: a hole's temporary fan
  std::vector<int> feature_vertex;       // per base vertex: its mesh vertex
  std::vector<std::vector<int>> paths;   // per base edge: mesh vertices from its first base vertex to its second
  std::vector<int> patch;                // per mesh triangle: its base triangle

  // Whether mesh triangle f fills a hole (a temporary fan), not the surface.
  bool in_fan(int f) const { return mesh.input_triangle(f) >= input_triangles; }
};

// A base triangle: corners k = 0, 1, 2 (base vertices) and the base edge from
// corner k to corner k + 1, with `reversed` when that path runs backwards.
struct BaseTriangle {
  std::array<int, 3> corners{};
  std::array<int, 3> edges{};
  std::array<bool, 3> reversed{};
};

struct ConsistentPartition {
  std::vector<PartitionSide> sides;        // A, then B
  std::vector<std::array<int, 2>> edges;   // per base edge: its base vertices
  std::vector<BaseTriangle> triangles;
  int given_features = 0;                  // base vertices 0 .. given - 1 are the caller's pairs
  int delayed_paths = 0;                   // tree pairs traced on different sides of a feature, put off
  int rerouted_paths = 0;                  // of those laid at last, re-routed to one side on both meshes
};

// Meshes with holes, closed by fans (intersurface/hole_rims.h): each rim is
// laid between its features, and a spoke from the centre to each, before
// anything else; every rim feature and centre must be among the features.
struct PartitionHoles {
  std::vector<HoleRim> rims;
  std::array<int, 2> first_fan{0, 0};  // per mesh: its first fan triangle (the input's triangle count)
};

// `features` are pairs of mesh vertices (A's, B's), at least one. Both
// meshes must be closed (holes fanned, see `holes`), manifold and oriented
// alike. Throws Error when the construction gets stuck.
ConsistentPartition consistent_partition(const TriangleMesh& a, const TriangleMesh& b,
                                         const std::vector<std::array<int, 2>>& features, int genus,
                                         const PartitionHoles& holes = {});

}  // namespace cmaps
