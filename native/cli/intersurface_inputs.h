// What `intersurface` and `transfer` read alike: feature pairs and map options.
#pragma once

#include <vector>

#include "arguments.h"
#include "consistent_maps/intersurface_map.h"

namespace cmaps::cli {

// Feature pairs of `intersurface`: {"name": [index_in_A, index_in_B], ...},
// every name with a vertex on both meshes; ranges and repeats are checked by
// the library (by pair index), here with the name.
std::vector<cmaps::FeaturePair> read_feature_pairs(const Arguments& args, const cmaps::TriangleMesh& a,
                                                   const cmaps::TriangleMesh& b);

// Options of the inter-surface map shared by intersurface and transfer.
cmaps::IntersurfaceOptions intersurface_options(const Arguments& args);

}  // namespace cmaps::cli
