// Meshes of genus >= 1 with holes (thesis 5.4, last part): every hole of both
// meshes is closed by a fan around a temporary centre vertex
// (paths/mesh_holes.h), the holes are paired, and each pair of rims gets at
// least three corresponding feature pairs, in the same order around both.
// The partition lays each rim between its features and a spoke from the
// centre to each of them before anything else (consistent_partition.h), so
// the fans become patches of their own: a hole maps onto its partner hole,
// a rim onto its partner rim, and the fans are dropped from the results.
#pragma once
#include <array>
#include <vector>

#include "intersurface/path_guide.h"
#include "paths/mesh_holes.h"

namespace cmaps {

struct HoleRim {
  std::array<int, 2> centre{-1, -1};         // the temporary centre vertices (A's, B's)
  std::vector<std::array<int, 2>> features;  // rim vertex pairs, in the order both loops run
  std::array<std::vector<int>, 2> loop;      // each mesh's rim, running alike on both
};

// `pairs`: the caller's feature pairs; `b_turned`: B's triangles are turned
// to run like A's (so its loops run the other way). A pair on two rims pairs
// those holes and is one of their rim features; other holes pair by nearest
// centres in A's frame (`guide`), their rims start at A's loop start and B's
// vertex nearest it. Rims with fewer than 3 features get more in the middle
// of their longest gaps, at the same fraction of the gap on both. The hole
// counts must be equal (intersurface_map refuses other pairs up front).
// Throws InvalidInput when a pair joins a rim vertex to a vertex off every
// rim, two pairs join one hole to two, or pairs run around a rim in
// different orders.
std::vector<HoleRim> pair_hole_rims(const ClosedMesh& a, const ClosedMesh& b,
                                    const std::vector<std::array<int, 2>>& pairs, bool b_turned,
                                    const PathGuide& guide);

}  // namespace cmaps
