// Where an inter-surface map puts the vertices, and how far it is from an
// isometry (symmetric Dirichlet by vertex sampling): see intersurface_map.h.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "consistent_maps/errors.h"
#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/mesh_check.h"
#include "intersurface/map_distortion.h"
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

double facing(const TriangleMesh& closed_source, const TriangleMesh& closed_target) {
  return signed_volume(closed_source) * signed_volume(closed_target) < 0 ? -1.0 : 1.0;
}

TriangleDistortion triangle_distortion(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image) {
  // Judged with their holes closed: an open mesh's volume changes sign with where the origin lies.
  return triangle_distortion(source, target, image,
                             facing(close_holes(source, true).mesh, close_holes(target, true).mesh));
}

TriangleDistortion triangle_distortion(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image, double facing) {
  if (image.size() != source.vertices.size())
    throw InvalidInput("the map has " + std::to_string(image.size()) + " images for " +
                       std::to_string(source.vertices.size()) + " vertices");
  const std::vector<Vec3> mapped = surface_positions(target, image);
  const double source_area = surface_area(source), target_area = surface_area(target);
  const double scale = target_area > 0 ? std::sqrt(source_area / target_area) : 1;  // target to the source's area
  // Normals of the target, turned to face like the source's when one of the
  // two meshes lists its triangles inwards (`facing`).
  // Unit normals, as both map optimizers weigh them (surface_image.h): an
  // image on a large triangle says no more about the surface under a chord
  // than one on a small triangle (weighted by area, a chord from a small
  // triangle across a crease onto a large one was judged by the large one
  // alone: 882 of the horse's triangles counted folded against the cow
  // where the optimizers' own test finds 221).
  const auto normal = [&](int t) {
    const Triangle& c = target.triangles[t];
    return Vec3(facing * (target.vertices[c[1]] - target.vertices[c[0]])
                             .cross(target.vertices[c[2]] - target.vertices[c[0]])
                             .normalized());
  };
  std::vector<std::vector<int>> star(target.vertices.size());
  for (int t = 0; t < int(target.triangles.size()); ++t)
    for (int v : target.triangles[t]) star[v].push_back(t);
  // The target triangles an image lies in: the one it is said to, and those
  // sharing the edge or vertex it lies on.
  const auto holding = [&](const SurfacePoint& p) {
    constexpr double kOnSide = 1e-9;
    const Triangle& c = target.triangles[p.triangle];
    for (int k = 0; k < 3; ++k)
      if (p.barycentric[(k + 1) % 3] <= kOnSide && p.barycentric[(k + 2) % 3] <= kOnSide) return star[c[k]];
    std::vector<int> found;
    for (int k = 0; k < 3; ++k)
      if (p.barycentric[k] <= kOnSide)  // on the side opposite corner k
        for (int t : star[c[(k + 1) % 3]])
          if (std::count(target.triangles[t].begin(), target.triangles[t].end(), c[(k + 2) % 3])) found.push_back(t);
    return found.empty() ? std::vector<int>{p.triangle} : found;
  };
  // The surface's normal where a triangle's images lie: a target triangle
  // holding all three when there is one (a mesh mapped onto itself folds
  // nothing, though an image at a vertex may be said to lie in any triangle
  // of its star, whose normals at a sharp crease can face against this
  // one's: the cow had 32 triangles counted folded so, the horse 40), else
  // the normals of the triangles each is said to lie in, summed.
  const auto surface_normal_at = [&](const SurfacePoint* corner[3]) {
    const std::vector<int> first = holding(*corner[0]), second = holding(*corner[1]), third = holding(*corner[2]);
    for (int t : first)
      if (std::count(second.begin(), second.end(), t) && std::count(third.begin(), third.end(), t)) return normal(t);
    return Vec3(normal(corner[0]->triangle) + normal(corner[1]->triangle) + normal(corner[2]->triangle));
  };

  const std::size_t m = source.triangles.size();
  TriangleDistortion d{std::vector<double>(m), std::vector<char>(m, 0), std::vector<double>(m)};
  for (std::size_t f = 0; f < m; ++f) {
    const Triangle& t = source.triangles[f];
    const Vec3 p[3] = {source.vertices[t[0]], source.vertices[t[1]], source.vertices[t[2]]};
    const Vec3 q[3] = {scale * mapped[t[0]], scale * mapped[t[1]], scale * mapped[t[2]]};
    const Vec3 nq = (q[1] - q[0]).cross(q[2] - q[0]);
    const SurfacePoint* corner[3] = {&image[t[0]], &image[t[1]], &image[t[2]]};
    const Vec3 surface_normal = surface_normal_at(corner);
    d.flipped[f] = nq.dot(surface_normal) < 0;
    const double e = symmetric_dirichlet(p, q, &d.area[f]);
    d.symmetric_dirichlet[f] = d.area[f] <= 0                     ? std::numeric_limits<double>::quiet_NaN()
                               : 0.5 * nq.norm() <= 1e-14 * source_area ? std::numeric_limits<double>::infinity()
                                                                        : e;
    d.area[f] = std::max(d.area[f], 0.0);
  }
  return d;
}

MapDistortion summarize(const TriangleDistortion& per_triangle) {
  MapDistortion d;
  double energy = 0, area = 0;
  std::vector<double> energies;  // per source triangle of non-zero area (zero-area ones carry no energy)
  energies.reserve(per_triangle.area.size());
  for (std::size_t f = 0; f < per_triangle.area.size(); ++f) {
    d.flipped += per_triangle.flipped[f];
    const double e = per_triangle.symmetric_dirichlet[f];
    if (std::isnan(e)) continue;
    energies.push_back(e);
    if (std::isinf(e)) {
      ++d.degenerate;
      continue;
    }
    energy += per_triangle.area[f] * e;
    area += per_triangle.area[f];
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

MapDistortion measure_intersurface_map(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image) {
  return summarize(triangle_distortion(source, target, image));
}

MapDistortion measure_intersurface_map(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image, double facing) {
  return summarize(triangle_distortion(source, target, image, facing));
}

}  // namespace cmaps
