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

namespace {

// Whether great-circle arcs ab and cd (each shorter than a half circle) cross
// at an interior point of both.
bool arcs_cross(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 n1 = a.cross(b), n2 = c.cross(d);
  const double sc = n1.dot(c), sd = n1.dot(d), ta = n2.dot(a), tb = n2.dot(b);
  if (!((sc > 0 && sd < 0) || (sc < 0 && sd > 0))) return false;
  if (!((ta > 0 && tb < 0) || (ta < 0 && tb > 0))) return false;
  const Vec3 x1 = std::abs(sd) * c + std::abs(sc) * d, x2 = std::abs(tb) * a + std::abs(ta) * b;
  return x1.dot(x2) > 0;
}

bool positive(const Vec3& x, const Vec3& y, const Vec3& z) {
  return x.dot(y.cross(z)) > 1e-12 * (y - x).cross(z - x).norm();
}

}  // namespace

bool force_edges(const std::vector<Vec3>& points, std::vector<Triangle>& triangles,
                 const std::vector<std::array<int, 2>>& required) {
  auto has_edge = [&](int u, int w) {
    for (const Triangle& t : triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] == u && t[(k + 1) % 3] == w) return true;
    return false;
  };
  auto is_required = [&](int u, int w) {
    for (const auto& r : required)
      if ((r[0] == u && r[1] == w) || (r[0] == w && r[1] == u)) return has_edge(u, w);
    return false;
  };
  for (const auto& r : required) {
    const int u = r[0], w = r[1];
    for (int flips = 0; !has_edge(u, w); ++flips) {
      if (flips > 64 * static_cast<int>(triangles.size())) return false;
      bool flipped = false;
      std::map<std::pair<int, int>, int> owner;
      for (int f = 0; f < static_cast<int>(triangles.size()); ++f)
        for (int k = 0; k < 3; ++k) owner[{triangles[f][k], triangles[f][(k + 1) % 3]}] = f;
      // Flip the first crossing edge whose quadrilateral is convex; the
      // order rotates with `flips` so that no pair of flips repeats forever.
      const int count = static_cast<int>(triangles.size());
      for (int step = 0; step < count && !flipped; ++step) {
        const int f = (step + flips) % count;
        for (int k = 0; k < 3 && !flipped; ++k) {
          const int i = triangles[f][k], j = triangles[f][(k + 1) % 3], p = triangles[f][(k + 2) % 3];
          if (i == u || i == w || j == u || j == w) continue;
          if (!arcs_cross(points[u], points[w], points[i], points[j]) || is_required(i, j)) continue;
          const auto it = owner.find({j, i});
          if (it == owner.end()) return false;
          const int g = it->second;
          const Triangle& other = triangles[g];
          const int q =
              other[0] != i && other[0] != j ? other[0] : other[1] != i && other[1] != j ? other[1] : other[2];
          if (p == q || owner.count({p, q}) || !positive(points[p], points[i], points[q]) ||
              !positive(points[q], points[j], points[p]))
            continue;
          triangles[f] = {p, i, q};
          triangles[g] = {q, j, p};
          flipped = true;
        }
      }
      if (!flipped) return false;
    }
  }
  return true;
}

}  // namespace cmaps
