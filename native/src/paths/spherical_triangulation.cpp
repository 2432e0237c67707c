#include "paths/spherical_triangulation.h"

#include <cmath>
#include <map>

namespace cmaps {
namespace {

double orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  return (b - a).cross(c - a).dot(p - a);
}

// The normal of a plane through all points, if there is one.
std::optional<Vec3> common_plane(const std::vector<Vec3>& p) {
  for (size_t i = 1; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) {
      const Vec3 n = (p[i] - p[0]).cross(p[j] - p[0]);
      if (n.norm() < 1e-9) continue;
      for (const Vec3& q : p)
        if (std::abs(n.normalized().dot(q - p[0])) > 1e-9) return std::nullopt;
      return n.normalized();
    }
  return Vec3(0, 0, 1);  // all points collinear or equal
}

}  // namespace

std::optional<std::vector<Triangle>> convex_hull_on_sphere(const std::vector<Vec3>& points) {
  const int n = static_cast<int>(points.size());
  if (n < 4 || common_plane(points)) return std::nullopt;
  // Perturb deterministically so that no four points are cocircular.
  std::vector<Vec3> p(points);
  for (int i = 0; i < n; ++i)
    p[i] = (p[i] + 1e-7 * Vec3(std::sin(1.3 + 7.1 * i), std::sin(2.9 + 3.7 * i), std::sin(0.7 + 5.3 * i)))
               .normalized();
  // Initial tetrahedron from the first four points in general position.
  int a = 0, b = 1, c = -1, d = -1;
  for (int i = 2; i < n && c < 0; ++i)
    if ((p[b] - p[a]).cross(p[i] - p[a]).norm() > 1e-12) c = i;
  for (int i = 2; i < n && d < 0 && c >= 0; ++i)
    if (i != c && std::abs(orient(p[a], p[b], p[c], p[i])) > 1e-12) d = i;
  if (c < 0 || d < 0) return std::nullopt;
  if (orient(p[a], p[b], p[c], p[d]) > 0) std::swap(b, c);
  std::vector<Triangle> faces{{a, b, c}, {a, d, b}, {b, d, c}, {c, d, a}};

  for (int i = 0; i < n; ++i) {
    if (i == a || i == b || i == c || i == d) continue;
    // Directed edges of the visible faces; an edge whose twin is not visible is on the horizon.
    std::map<std::pair<int, int>, bool> visible_edges;
    std::vector<Triangle> kept;
    for (const Triangle& f : faces) {
      if (orient(p[f[0]], p[f[1]], p[f[2]], p[i]) > 0) {
        for (int k = 0; k < 3; ++k) visible_edges[{f[k], f[(k + 1) % 3]}] = true;
      } else {
        kept.push_back(f);
      }
    }
    for (const auto& [edge, unused] : visible_edges)
      if (!visible_edges.count({edge.second, edge.first})) kept.push_back({edge.first, edge.second, i});
    faces = std::move(kept);
  }
  return faces;
}

std::optional<Vec3> point_to_enclose_origin(const std::vector<Vec3>& points) {
  if (const auto plane = common_plane(points)) {
    // Add the pole on the origin's side of the plane.
    const Vec3 n = plane->dot(points.front()) >= 0 ? *plane : Vec3(-*plane);
    return Vec3(-n);
  }
  const auto hull = convex_hull_on_sphere(points);
  for (const Triangle& t : *hull) {
    const Vec3 &x = points[t[0]], &y = points[t[1]], &z = points[t[2]];
    const Vec3 normal = (y - x).cross(z - x);
    if (x.dot(y.cross(z)) <= 1e-9 * normal.norm()) return normal.normalized();
  }
  return std::nullopt;
}

}  // namespace cmaps
