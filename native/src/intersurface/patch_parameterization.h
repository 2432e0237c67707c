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

struct PatchParameterization {
  std::vector<std::unordered_map<int, Vec2>> uv;  // per base triangle: mesh vertex -> canonical point
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

// Per input vertex of `source`: the point of `target` with the same canonical
// coordinates, on `target_input`'s triangles. Features that are input
// vertices on both sides map exactly onto their partners.
std::vector<InputLocation> map_vertices(const PartitionSide& source, const PatchParameterization& source_uv,
                                        const PartitionSide& target, const PatchParameterization& target_uv,
                                        const TriangleMesh& target_input, int threads);

// Per corner k of input triangle t of `source_input` (entry 3 t + k): the
// image on `target_input` of the point of t next to that corner (input
// barycentric 1 - 2 kCornerNudge there, kCornerNudge at the other two), for
// per-corner values. That point is no feature: it is mapped as it lands.
std::vector<InputLocation> map_corners(const PartitionSide& source, const PatchParameterization& source_uv,
                                       const PartitionSide& target, const PatchParameterization& target_uv,
                                       const TriangleMesh& source_input, const TriangleMesh& target_input,
                                       int threads);

}  // namespace cmaps
