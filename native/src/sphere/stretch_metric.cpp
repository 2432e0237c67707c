#include "consistent_maps/stretch_metric.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cmaps {

TriangleStretch triangle_stretch(const Vec3& d0, const Vec3& d1, const Vec3& d2, const Vec3& m0,
                                 const Vec3& m1, const Vec3& m2) {
  // Orthonormal 2D frame (s, t) in the plane of the domain triangle.
  const Vec3 e1 = d1 - d0, e2 = d2 - d0;
  const Vec3 normal = e1.cross(e2);
  const double twice_area = normal.norm();
  const double len1 = e1.norm();
  if (!(twice_area > 0) || !(len1 > 0) || !std::isfinite(twice_area)) {
    const double inf = std::numeric_limits<double>::infinity();
    return {inf, inf};
  }
  const Vec3 s_axis = e1 / len1;
  const Vec3 t_axis = normal.cross(s_axis) / twice_area;
  const double s1 = len1, t1 = 0, s2 = e2.dot(s_axis), t2 = e2.dot(t_axis);
  // Partial derivatives of the linear map (s, t) -> surface; corner 0 at the origin.
  const Vec3 ds = (m0 * (t1 - t2) + m1 * t2 - m2 * t1) / twice_area;
  const Vec3 dt = (m0 * (s2 - s1) - m1 * s2 + m2 * s1) / twice_area;
  const double a = ds.squaredNorm(), b = ds.dot(dt), c = dt.squaredNorm();
  const double big = 0.5 * ((a + c) + std::sqrt((a - c) * (a - c) + 4 * b * b));
  return {std::sqrt(0.5 * (a + c)), std::sqrt(big)};
}

double signed_spherical_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  // Van Oosterom & Strackee: tan(E/2) = det / (1 + a.b + b.c + c.a).
  const double det = a.dot(b.cross(c));
  return 2 * std::atan2(det, 1 + a.dot(b) + b.dot(c) + c.dot(a));
}

bool SphericalMapReport::bijective() const {
  return flipped == 0 && degenerate == 0 && std::abs(spherical_area_sum - 4 * M_PI) < 1e-6;
}

SphericalMapReport measure_spherical_map(const TriangleMesh& mesh, const std::vector<Vec3>& sphere) {
  SphericalMapReport r;
  double weighted_l2_squared = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &a = sphere[t[0]], &b = sphere[t[1]], &c = sphere[t[2]];
    const double det = a.dot(b.cross(c));
    if (!std::isfinite(det) || det == 0) {
      ++r.degenerate;
    } else if (det < 0) {
      ++r.flipped;
    }
    r.spherical_area_sum += std::isfinite(det) ? signed_spherical_area(a, b, c) : 0.0;
    const Vec3 &p0 = mesh.vertices[t[0]], &p1 = mesh.vertices[t[1]], &p2 = mesh.vertices[t[2]];
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    r.surface_area += area;
    if (area == 0) continue;  // a zero-area surface triangle carries no stretch
    const TriangleStretch s = triangle_stretch(a, b, c, p0, p1, p2);
    weighted_l2_squared += area * s.l2 * s.l2;
    r.linf_stretch = std::max(r.linf_stretch, s.linf);
  }
  if (r.surface_area > 0) {
    r.l2_stretch = std::sqrt(weighted_l2_squared / r.surface_area);
    const double l2_squared = weighted_l2_squared / r.surface_area;
    r.efficiency = std::isfinite(l2_squared) && l2_squared > 0
                       ? (r.surface_area / (4 * M_PI)) / l2_squared : 0.0;
  }
  return r;
}

}  // namespace cmaps
