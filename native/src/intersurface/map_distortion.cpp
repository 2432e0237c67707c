// Where an inter-surface map puts the vertices, and how far it is from an
// isometry (symmetric Dirichlet by vertex sampling): see intersurface_map.h.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "consistent_maps/errors.h"
#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/mesh_check.h"
#include "intersurface/symmetric_dirichlet.h"
#include "paths/mesh_holes.h"

namespace cmaps {

std::vector<Vec3> surface_positions(const TriangleMesh& target, const std::vector<SurfacePoint>& points) {
  std::vector<Vec3> positions(points.size(), Vec3::Zero());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& p = points[i];
    if (p.triangle < 0 || p.triangle >= int(target.triangles.size()))
      throw InvalidInput("point " + std::to_string(i) + " lies on triangle " + std::to_string(p.triangle) +
                         " but the target has " + std::to_string(target.triangles.size()) + " triangles");
    for (int k = 0; k < 3; ++k) positions[i] += p.barycentric[k] * target.vertices[target.triangles[p.triangle][k]];
  }
  return positions;
}

MapDistortion measure_intersurface_map(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image) {
  if (image.size() != source.vertices.size())
    throw InvalidInput("the map has " + std::to_string(image.size()) + " images for " +
                       std::to_string(source.vertices.size()) + " vertices");
  const std::vector<Vec3> mapped = surface_positions(target, image);
  const double source_area = surface_area(source), target_area = surface_area(target);
  const double scale = target_area > 0 ? std::sqrt(source_area / target_area) : 1;  // target to the source's area
  // Normals of the target, turned to face like the source's when one of the
  // two meshes lists its triangles inwards (judged with their holes closed:
  // an open mesh's volume changes sign with where the origin lies).
  const double facing =
      signed_volume(close_holes(source, true).mesh) * signed_volume(close_holes(target, true).mesh) < 0 ? -1.0 : 1.0;
  const auto normal = [&](int t) {
    const Triangle& c = target.triangles[t];
    return Vec3(facing *
                (target.vertices[c[1]] - target.vertices[c[0]]).cross(target.vertices[c[2]] - target.vertices[c[0]]));
  };

  MapDistortion d;
  double energy = 0, area = 0;
  std::vector<double> energies;  // per source triangle of non-zero area
  energies.reserve(source.triangles.size());
  for (const Triangle& t : source.triangles) {
    const Vec3 &p0 = source.vertices[t[0]], &p1 = source.vertices[t[1]], &p2 = source.vertices[t[2]];
    const Vec3 q0 = scale * mapped[t[0]], q1 = scale * mapped[t[1]], q2 = scale * mapped[t[2]];
    const Vec3 nq = (q1 - q0).cross(q2 - q0);
    const Vec3 surface_normal = normal(image[t[0]].triangle) + normal(image[t[1]].triangle) +
                                normal(image[t[2]].triangle);
    if (nq.dot(surface_normal) < 0) ++d.flipped;
    const Vec3 p[3] = {p0, p1, p2}, q[3] = {q0, q1, q2};
    double ap;
    const double e = symmetric_dirichlet(p, q, &ap);
    if (ap <= 0) continue;  // zero-area source triangles carry no energy
    if (0.5 * nq.norm() <= 1e-14 * source_area) {
      ++d.degenerate;
      energies.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    energy += ap * e;
    area += ap;
    energies.push_back(e);
  }
  d.symmetric_dirichlet = area > 0 ? energy / area : std::numeric_limits<double>::infinity();
  d.median_symmetric_dirichlet = std::numeric_limits<double>::infinity();
  if (!energies.empty()) {
    const auto middle = energies.begin() + energies.size() / 2;
    std::nth_element(energies.begin(), middle, energies.end());
    d.median_symmetric_dirichlet = *middle;
  }
  return d;
}

}  // namespace cmaps
