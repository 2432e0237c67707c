// Two spherical maps composed into an inter-surface map (a point of one
// mesh goes to the point of the other with the same sphere point): the
// composition, its distortion, and its optimization. The genus-0 pair map
// and the consistent set's alignment with its reference member share them.
#pragma once
#include <utility>
#include <vector>

#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/intersurface_map.h"

namespace cmaps {

// Per source vertex: its image on `target` through the sphere; the `exact`
// (source, target) vertex pairs are put exactly on their partners.
std::vector<SurfacePoint> map_through_sphere(const std::vector<Vec3>& source_sphere, const TriangleMesh& target,
                                             const ConstrainedResult& target_map,
                                             const std::vector<std::pair<int, int>>& exact, int threads);

// One side of a composition being optimized: its vertices in `fixed` (and
// the corners of its holes' fans) never move.
struct ComposedSide {
  const TriangleMesh& mesh;
  ConstrainedResult& map;
  std::vector<int> fixed;
};

// Lowers the symmetric distortion of the composition (see MapOptimizer) by
// moving the sphere points of both sides.
void optimize_composition(ComposedSide a, ComposedSide b, int rounds, int sweeps, int threads,
                          const ProgressCallback& progress);

// The symmetric Dirichlet energy of the composition, A onto B plus B onto A
// (measure_intersurface_map, vertex images only).
double composition_dirichlet(const TriangleMesh& a, const ConstrainedResult& map_a, const TriangleMesh& b,
                             const ConstrainedResult& map_b, int threads);

}  // namespace cmaps
