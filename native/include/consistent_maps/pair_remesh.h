// Consistent remeshes of two surfaces mapped onto each other (an
// inter-surface map, any genus): the two meshes returned share one
// connectivity, vertex for vertex, each lying on its own surface.
//
// One surface, the carrier, is simplified by half-edge collapses (the
// progressive mesh's) whose quadric error and fold tests cover both its own
// geometry and its vertices' images on the partner; every remesh vertex is a
// carrier vertex, so it lies exactly on the carrier and its image exactly on
// the partner, and features (locked) stay at identical indices. Collapses
// removing triangles that face against the partner's surface go first, then
// edge flips split a folded triangle's quad along its other diagonal where
// that folds less on both surfaces, so a remesh folds far less than the map's
// vertex sampling. Holes stay holes: each is closed by a temporary fan while
// simplifying and its rim only shortens along itself.
#pragma once
#include <vector>

#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/mesh.h"

namespace cmaps {

struct PairRemesh {
  bool b_carries = false;           // whose vertices the remesh's are: A's (false) or B's (true)
  std::vector<int> carrier_vertex;  // the carrier's vertex each remesh vertex is
  std::vector<Triangle> triangles;  // over remesh vertices, oriented as the carrier's
  std::vector<Vec3> a_positions, b_positions;
  std::vector<int> feature_vertices;  // remesh vertex of each feature pair, in the order given
  // Remesh triangles facing against the surface they lie on (A or B).
  int folded_triangles = 0;
};

// `a_on_b`: one point of B per vertex of A (its image), `b_on_a` likewise (an
// inter-surface map's two directions; unused vertices are ignored and
// dropped). Simplifies to `target_vertices`, or as far as collapses go
// without folding a triangle, once with A carrying and once with B, and
// keeps the remesh with fewer folded triangles (a carrier whose images
// sample the other surface too sparsely folds more), then the one nearer
// the target. Throws InvalidInput for mismatched sizes, a point off the
// other mesh's triangles, a feature out of range or a target below 4,
// TopologyError unless both are manifold, consistently oriented surfaces
// (holes allowed).
PairRemesh remesh_pair(const TriangleMesh& a, const TriangleMesh& b, const std::vector<SurfacePoint>& a_on_b,
                       const std::vector<SurfacePoint>& b_on_a, const std::vector<FeaturePair>& features,
                       int target_vertices);

}  // namespace cmaps
