// Farthest-point sampling of a mesh's vertices, the automatic features of a
// pair given too few: straight-line distances, or distances along the edges,
// which find the tips of limbs lying side by side (a horse's four hooves are
// close in space but far apart along the surface).
#pragma once
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// The vertex farthest from the centroid: the automatic feature of a mesh.
int farthest_from_centroid(const TriangleMesh& mesh);

// Farthest-point sampling from seeds, keeping per vertex the distance to the
// nearest of the seeds taken so far (squared in a straight line).
class Spread {
 public:
  // Along the edges when `along_edges`, else in a straight line.
  Spread(const TriangleMesh& mesh, bool along_edges);

  // The vertex farthest from `seeds` (the first seeds unchanged since the
  // last call), -1 when every vertex is a seed or the rest is unreachable.
  int next(const std::vector<int>& seeds);

 private:
  void reach_from(int seed);  // lowers `distance_` by the distances from seed

  const TriangleMesh& mesh_;
  std::vector<std::vector<int>> neighbours_;  // empty: straight-line distances
  std::vector<double> distance_;
  std::size_t taken_ = 0;  // seeds already in distance_
};

// The automatic feature of restart `start`: the start-th of the vertices
// spread (in a straight line) from the one farthest from the centroid.
int spread_vertex(const TriangleMesh& mesh, int start);

}  // namespace cmaps
