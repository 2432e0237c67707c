#include "consistent_maps/remesh.h"

#include <cmath>
#include <string>

#include "consistent_maps/errors.h"
#include "consistent_maps/sphere_locator.h"

namespace cmaps {

std::vector<Vec3> resample(const TriangleMesh& mesh, const std::vector<Vec3>& sphere,
                           const std::vector<Vec3>& samples, int threads) {
  if (sphere.size() != mesh.vertices.size())
    throw InvalidInput("resample: " + std::to_string(sphere.size()) + " sphere points for " +
                       std::to_string(mesh.vertices.size()) + " vertices");
  const SphereLocator locator(sphere, mesh.triangles);
  return locator.interpolate(mesh.vertices, locator.locate_all(samples, threads), threads);
}

std::vector<int> snap_features(std::vector<Vec3>& samples, const std::vector<Vec3>& feature_directions) {
  if (samples.empty() && !feature_directions.empty()) throw InvalidInput("snap features: no samples");
  std::vector<int> chosen;
  std::vector<int> owner(samples.size(), -1);  // feature already snapped to each sample
  for (size_t f = 0; f < feature_directions.size(); ++f) {
    const Vec3& d = feature_directions[f];
    if (!d.allFinite() || d.isZero(0))
      throw InvalidInput("snap features: direction of feature " + std::to_string(f) + " is zero or not finite");
    const Vec3 unit = d.normalized();
    // Brute force: a few dozen features against ~10^5 samples is cheap.
    int nearest = 0;
    for (size_t s = 1; s < samples.size(); ++s)
      if (samples[s].dot(unit) > samples[nearest].dot(unit)) nearest = static_cast<int>(s);
    if (owner[nearest] >= 0)
      throw InvalidInput("snap features: features " + std::to_string(owner[nearest]) + " and " + std::to_string(f) +
                         " both snap to sample " + std::to_string(nearest) + "; use a finer grid");
    owner[nearest] = static_cast<int>(f);
    chosen.push_back(nearest);
  }
  // Moved only now so each feature's nearest sample is judged on the original grid.
  for (size_t f = 0; f < chosen.size(); ++f) samples[chosen[f]] = feature_directions[f].normalized();
  return chosen;
}

}  // namespace cmaps
