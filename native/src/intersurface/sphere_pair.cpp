#include "intersurface/sphere_pair.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "common/parallel_for.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/sphere_locator.h"

namespace cmaps {
namespace {

// Barycentric coordinates of x w.r.t. triangle (p0, p1, p2), projected onto
// its plane, clamped to the triangle and normalized.
std::array<double, 3> project(const Vec3& x, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0, d = x - p0;
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2), det = a * c - b * b;
  std::array<double, 3> w{1.0 / 3, 1.0 / 3, 1.0 / 3};
  if (det > 0) {
    const double s = (c * d.dot(e1) - b * d.dot(e2)) / det, t = (a * d.dot(e2) - b * d.dot(e1)) / det;
    w = {std::max(0.0, 1 - s - t), std::max(0.0, s), std::max(0.0, t)};
  }
  const double sum = w[0] + w[1] + w[2];
  if (sum > 0) for (double& v : w) v /= sum;
  else w = {1, 0, 0};
  return w;
}

// A point of `map`'s refined triangulation (triangle, barycentric) as a point
// of the input triangle it lies in, w.r.t. that triangle's corners.
SurfacePoint to_input(const TriangleMesh& mesh, const ConstrainedResult& map, const SphereLocation& at) {
  const int n = int(mesh.vertices.size());
  SurfacePoint p;
  p.triangle = map.input_triangle[at.triangle];
  const Triangle& corners = mesh.triangles[p.triangle];
  double stray = 0;  // weight on vertices that are not corners (never, up to the refinement's bookkeeping)
  Vec3 x = Vec3::Zero();
  const auto add = [&](int v, double w) {
    x += w * mesh.vertices[v];
    for (int j = 0; j < 3; ++j)
      if (corners[j] == v) {
        p.barycentric[j] += w;
        return;
      }
    stray += std::abs(w);
  };
  const Triangle& refined = map.triangles[at.triangle];
  for (int k = 0; k < 3; ++k) {
    const int c = refined[k];
    const double w = at.barycentric[k];
    if (c < n) {
      add(c, w);
    } else {
      const SteinerVertex& s = map.steiner[c - n];
      for (int j = 0; j < 3; ++j)
        if (s.vertices[j] >= 0) add(s.vertices[j], w * s.weights[j]);
    }
  }
  if (stray > 1e-12) {
    p.barycentric = project(x, mesh.vertices[corners[0]], mesh.vertices[corners[1]], mesh.vertices[corners[2]]);
    return p;
  }
  double sum = 0;
  for (double& w : p.barycentric) sum += (w = std::max(0.0, w));
  for (double& w : p.barycentric) w /= sum;
  return p;
}

}  // namespace

std::vector<SurfacePoint> map_through_sphere(const std::vector<Vec3>& source_sphere, const TriangleMesh& target,
                                             const ConstrainedResult& target_map,
                                             const std::vector<std::pair<int, int>>& exact, int threads) {
  // Holes are closed by their temporary fans so that every direction lands
  // somewhere. Both meshes' boundaries lie on the same great-circle arcs (a
  // chord projects onto its arc), so only directions on a boundary, up to
  // rounding, land in a fan: they move onto its boundary edge, on the real
  // triangle across it.
  const ParameterizedSurface surface = parameterized_surface(target, target_map, /*close_holes=*/true);
  const SphereLocator locator(surface.sphere, surface.surface.triangles);
  std::vector<SphereLocation> located = locator.locate_all(source_sphere, threads);
  if (target_map.holes > 0) {
    const int real = int(target_map.triangles.size()), first_centre = int(surface.sphere.size()) - target_map.holes;
    std::map<std::pair<int, int>, int> beside;  // boundary edge (u, v) of a fan -> the real triangle with edge (v, u)
    for (int f = 0; f < real; ++f)
      for (int k = 0; k < 3; ++k) beside[{target_map.triangles[f][(k + 1) % 3], target_map.triangles[f][k]}] = f;
    for (SphereLocation& at : located) {
      if (at.triangle < real) continue;
      const Triangle& fan = surface.surface.triangles[at.triangle];
      const int k = fan[0] >= first_centre ? 0 : fan[1] >= first_centre ? 1 : 2;
      const int u = fan[(k + 1) % 3], v = fan[(k + 2) % 3];
      double wu = at.barycentric[(k + 1) % 3], wv = at.barycentric[(k + 2) % 3];
      if (!(wu + wv > 0)) wu = wv = 1;
      const auto edge = beside.find({u, v});
      if (edge == beside.end()) throw Error("internal error: a hole's boundary edge has no triangle");
      at.triangle = edge->second;
      const Triangle& t = target_map.triangles[at.triangle];
      for (int j = 0; j < 3; ++j) at.barycentric[j] = t[j] == u ? wu / (wu + wv) : t[j] == v ? wv / (wu + wv) : 0;
    }
  }
  std::vector<SurfacePoint> points(located.size());
  parallel_for(int(located.size()), threads, [&](int i) { points[i] = to_input(target, target_map, located[i]); });

  std::vector<int> incident(target.vertices.size(), -1);  // one triangle per vertex
  for (std::size_t t = 0; t < target.triangles.size(); ++t)
    for (int v : target.triangles[t])
      if (incident[v] < 0) incident[v] = int(t);
  for (const auto& [from, to] : exact) {
    SurfacePoint& p = points[from];
    p.triangle = incident[to];
    for (int j = 0; j < 3; ++j) p.barycentric[j] = target.triangles[p.triangle][j] == to ? 1 : 0;
  }
  return points;
}

double composition_dirichlet(const TriangleMesh& a, const ConstrainedResult& map_a, const TriangleMesh& b,
                             const ConstrainedResult& map_b, int threads) {
  return measure_intersurface_map(a, b, map_through_sphere(map_a.sphere, b, map_b, {}, threads)).symmetric_dirichlet +
         measure_intersurface_map(b, a, map_through_sphere(map_b.sphere, a, map_a, {}, threads)).symmetric_dirichlet;
}

}  // namespace cmaps
