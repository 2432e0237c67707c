// The map between two consistently partitioned meshes: every patch of both
// is parameterized onto one canonical equilateral triangle per base
// triangle. Boundaries go by normalized arc length along each path (so the
// two patches beside a path agree on it and the map is continuous across
// patches), interiors by a convex-combination embedding (mean-value weights,
// reweighted for stretch), which is bijective for a disk with a convex
// boundary and no edge between two boundary vertices (Floater 2003); such
// edges are split first. A point of
// one mesh maps to the point of the other mesh with the same canonical
// coordinates in the partner patch.
#pragma once
#include <Eigen/Core>
#include <unordered_map>
#include <vector>

#include "intersurface/consistent_partition.h"

namespace cmaps {

using Vec2 = Eigen::Vector2d;

// The canonical triangle: base triangle corner k sits at kCanonicalCorner[k],
// base edge k runs from corner k to corner k + 1.
inline const Vec2 kCanonicalCorner[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, 0.86602540378443864676)};

struct PatchParameterization {
  std::vector<std::unordered_map<int, Vec2>> uv;  // per base triangle: mesh vertex -> canonical point
  // Per base triangle: mesh vertex -> the factor by which the stretch
  // reweighting multiplied its neighbours' mean-value weights towards it in
  // the embedding that gave uv (1 where it kept no round).
  std::vector<std::unordered_map<int, double>> pull;
};

// Rounds of stretch reweighting after the mean-value embedding (see parameterize_patches).
constexpr int kPatchStretchRounds = 10;

// Splits the side's edges between two path vertices that are not path
// edges (a patch's chords), then parameterizes every patch: mean-value
// weights, then up to `stretch_rounds` rounds of stretch reweighting
// (Yoshizawa, Belyaev & Seidel 2004), each kept only if it lowers the
// patch's L2 stretch.
PatchParameterization parameterize_patches(PartitionSide& side, const ConsistentPartition& partition,
                                           int stretch_rounds = kPatchStretchRounds);

// A patch's L2 stretch (Sander et al. 2001) from the canonical triangle onto
// the surface: the root of the area-weighted mean of its triangles' squared stretch.
double patch_stretch(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces);

// A point of a partitioned mesh in its input triangulation: input triangle
// and barycentric weights in that triangle's corner order.
struct InputLocation {
  int triangle = -1;
  std::array<double, 3> barycentric{0, 0, 0};
};

// Features of `source` that are input vertices on both sides: their images
// (per input vertex of `source`) set exactly onto their partners.
void snap_features(const PartitionSide& source, const PartitionSide& target, const TriangleMesh& target_input,
                   std::vector<InputLocation>& image);

// Per base triangle: the side's triangles in it.
std::vector<std::vector<int>> faces_by_patch(const PartitionSide& side, int patches);

// The side's triangles turned over in their patch's embedding: facing against
// the patch's own orientation (the sign of its summed area) or of zero area.
// 0 when every patch is embedded bijectively. Holes' fans are left out.
int turned_in_patches(const PartitionSide& side, const PatchParameterization& uv);

// A point of a side's refined mesh (triangle, weights) on its input triangle.
InputLocation to_input(const PartitionSide& side, const TriangleMesh& input, int face, const std::array<double, 3>& w);

// A point of a side's refined mesh: triangle and barycentric weights.
struct RefinedPoint {
  int face = -1;
  std::array<double, 3> weights{0, 0, 0};
};

// Per corner k of input triangle t of `source_input` (entry 3 t + k): the
// point of t next to that corner (input barycentric 1 - 2 kCornerNudge
// there, kCornerNudge at the other two) in the refined mesh, for per-corner
// values. That point is no feature: it is mapped as it lands.
std::vector<RefinedPoint> corner_points(const PartitionSide& source, const TriangleMesh& source_input, int threads);

}  // namespace cmaps
