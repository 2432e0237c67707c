// Balancing the areas of corresponding patches. A partition traced on two
// different shapes can give one base triangle 1 % of one surface and 48 % of
// the other (kitten - rocker arm); inside a patch the map pairs two
// embeddings of one canonical triangle, so no optimization inside the
// patches undoes such a squeeze. Here the paths move instead: a path whose
// two patches split their union's area very differently on the two sides
// is traced again on both, inside those two patches, as a level set of the
// harmonic function (mean-value weights) that is 0 on one patch's other
// sides and 1 on the other's, at the level where the two patches split
// their area in the ratio halfway (geometrically) between the sides'. Such a
// level set is one simple curve between the path's ends, so the base
// connectivity, the cyclic orders at the base vertices and every other path
// stay as they are. A level curve that would run along another path (the
// patch between them pinched into slivers) is not taken: the path goes half
// or a quarter of the way instead, or stays. Rounds over all paths spread
// the balance over the base mesh.
#pragma once
#include "intersurface/consistent_partition.h"

namespace cmaps {

struct PatchBalance {
  double worst_before = 1, worst_after = 1;  // largest ratio of a patch's area shares between the sides (>= 1)
  int retraced = 0;                          // paths traced again (one side each)
};

// The largest ratio between a patch's shares of the two sides' areas (1:
// every patch takes the same share of both; a hole's fan counts nothing).
double patch_area_ratio(const ConsistentPartition& partition);

// Moves paths of both sides (their meshes gain Steiner vertices where the
// new paths cross edges), `rounds` times over every path whose two patches'
// area ratios differ by more than half between the sides. Paths between two
// sides of one patch, between two patches that share another path, and
// beside a hole's fan (its rim and spokes) stay.
PatchBalance balance_patch_areas(ConsistentPartition& partition, int rounds);

}  // namespace cmaps
