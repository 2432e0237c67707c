// What `intersurface` and `transfer` share: feature pairs and map options read
// alike, the map reported alike.
#pragma once

#include <string>
#include <vector>

#include "arguments.h"
#include "outcome.h"
#include "consistent_maps/intersurface_map.h"

namespace cmaps::cli {

// Feature pairs of `intersurface`: {"name": [index_in_A, index_in_B], ...},
// every name with a vertex on both meshes; ranges and repeats are checked by
// the library (by pair index), here with the name. `names`, when given,
// receives each pair's name.
std::vector<cmaps::FeaturePair> read_feature_pairs(const Arguments& args, const cmaps::TriangleMesh& a,
                                                   const cmaps::TriangleMesh& b,
                                                   std::vector<std::string>* names = nullptr);

// Options of the inter-surface map shared by intersurface and transfer.
cmaps::IntersurfaceOptions intersurface_options(const Arguments& args);

// The map's --json keys shared by both commands, per direction or mesh in the
// order of the command's inputs: `swapped` when the map ran from the second
// input onto the first; `given` feature pairs came from the command line.
void report_map(const cmaps::IntersurfaceResult& map, std::size_t given, bool swapped, Outcome& out);

}  // namespace cmaps::cli
