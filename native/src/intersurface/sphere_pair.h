// Two spherical maps composed into an inter-surface map (a point of one
// mesh goes to the point of the other with the same sphere point) and its
// distortion: shared by the genus-0 pair map and the consistent set's
// alignment with its seeding member.
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

// The symmetric Dirichlet energy of the composition, A onto B plus B onto A
// (measure_intersurface_map, vertex images only).
double composition_dirichlet(const TriangleMesh& a, const ConstrainedResult& map_a, const TriangleMesh& b,
                             const ConstrainedResult& map_b, int threads);

}  // namespace cmaps
