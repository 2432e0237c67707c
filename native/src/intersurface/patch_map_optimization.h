// Local optimization of a patch-wise inter-surface map for its symmetric
// Dirichlet energy: the source's free vertices (off the partition's paths)
// move inside their patch's canonical triangle, and the vertices inside a
// path slide along it (the same fraction of the base edge in both patches
// beside it, between their path neighbours), each to a lower energy of its
// triangles mapped onto the target (chords between the images, the target
// scaled to the source's area), never so far that a triangle of the source's
// embedding turns over. The embedding stays a bijection onto each canonical
// triangle and continuous across the paths, so the map stays continuous and
// bijective; the paths themselves and the base vertices do not move. Before
// the sweeps, each patch's interior is embedded again with weights scaled by
// the map's area ratio (a global step the vertex moves cannot take; kept
// only where it lowers the energy).
#pragma once
#include "intersurface/patch_parameterization.h"

namespace cmaps {

struct MapOptimization {
  double energy_before = 0, energy_after = 0;  // area-weighted mean over the source's patch triangles
  int moves = 0;
};

// Rounds of re-embedding each patch for the target's areas (before the sweeps).
constexpr int kPatchAreaRounds = 10;

MapOptimization optimize_patch_map(const PartitionSide& source, PatchParameterization& source_uv,
                                   const PartitionSide& target, const PatchParameterization& target_uv,
                                   int sweeps, int threads, int area_rounds = kPatchAreaRounds);

}  // namespace cmaps
