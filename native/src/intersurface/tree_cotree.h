// Non-separating cycles on one side of a growing partition by tree-cotree
// (Eppstein 2003; Erickson & Whittlesey 2005): a shortest-path tree from a
// root, a cotree of the faces across the remaining edges, and the shortest
// loop that one of the edges left over closes with the tree.
#pragma once

#include <vector>

#include "intersurface/partition_network.h"

namespace cmaps::partition {

// The shortest non-separating cycle that tree-cotree finds from `root` on
// `side` (steps weighted by `factor` when given), as a vertex list from its
// apex back to it; empty when none.
std::vector<int> tree_cotree_cycle(const Side& side, int root, const Side::StepFactor* factor);

}  // namespace cmaps::partition
