// Colours and texture coordinates carried from one mesh to another through an
// inter-surface map (see attribute_transfer.h).
#include "consistent_maps/attribute_transfer.h"

#include <complex>
#include <deque>
#include <map>
#include <tuple>
#include <unordered_map>

#include "common/triangle_neighbours.h"

namespace cmaps {
namespace {

using Uv = std::array<double, 2>;
using Complex = std::complex<double>;

// z -> a z + b: how texture coordinates of one triangle's chart become another's.
struct Transition {
  Complex a{1, 0}, b{0, 0};
  Uv apply(const Uv& uv) const {
    const Complex z = a * Complex(uv[0], uv[1]) + b;
    return {z.real(), z.imag()};
  }
  Transition then(const Transition& next) const { return {next.a * a, next.a * b + next.b}; }  // next after this
};

// Texture charts of the source's triangles: the neighbours across each edge
// and the transition of coordinates across it (identity inside a chart; across
// a seam, the similarity taking the edge's coordinates in one triangle onto
// those in the other, e.g. u + 1 for a cylinder's seam).
class Charts {
 public:
  Charts(const std::vector<Triangle>& triangles, const std::vector<std::array<int, 3>>& triangle_uvs,
         const std::vector<Uv>& uvs)
      : triangles_(triangles), triangle_uvs_(triangle_uvs), uvs_(uvs), neighbours_(triangle_neighbours(triangles)) {}

  // The coordinates of corner vertex v as seen from triangle t.
  Uv at(int t, int v) const {
    for (int k = 0; k < 3; ++k)
      if (triangles_[t][k] == v) return uvs_[triangle_uvs_[t][k]];
    return {0, 0};
  }

  // Coordinates in triangle `from`'s chart expressed in neighbour `to`'s chart.
  Transition across(int from, int to, int edge) const {
    const int p = triangles_[from][edge], q = triangles_[from][(edge + 1) % 3];
    const Uv fp = at(from, p), fq = at(from, q), tp = at(to, p), tq = at(to, q);
    if (fp == tp && fq == tq) return {};
    const Complex f0(fp[0], fp[1]), f1(fq[0], fq[1]), t0(tp[0], tp[1]), t1(tq[0], tq[1]);
    Transition x;
    if (std::abs(f1 - f0) > 1e-12) x.a = (t1 - t0) / (f1 - f0);
    x.b = t0 - x.a * f0;
    return x;
  }

  // The transition from triangle `from`'s chart to `to`'s along the fewest
  // triangles between them (at most `limit` steps; identity beyond).
  Transition between(int from, int to, int limit = 64) const {
    if (from == to) return {};
    std::unordered_map<int, std::pair<int, int>> parent{{from, {-1, -1}}};  // triangle -> (previous, edge)
    std::deque<std::pair<int, int>> queue{{from, 0}};
    while (!queue.empty()) {
      const auto [t, depth] = queue.front();
      queue.pop_front();
      if (t == to) break;
      if (depth >= limit) continue;
      for (int k = 0; k < 3; ++k) {
        const int n = neighbours_[t][k];
        if (n >= 0 && parent.emplace(n, std::make_pair(t, k)).second) queue.push_back({n, depth + 1});
      }
    }
    if (!parent.count(to)) return {};
    std::vector<std::pair<int, int>> steps;  // (triangle, edge index in it) from `to` back to `from`
    for (int t = to; parent.at(t).first >= 0; t = parent.at(t).first) steps.push_back(parent.at(t));
    Transition x;
    int current = from;
    for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
      const int next = neighbours_[it->first][it->second];
      x = x.then(across(current, next, it->second));
      current = next;
    }
    return x;
  }

 private:
  const std::vector<Triangle>& triangles_;
  const std::vector<std::array<int, 3>>& triangle_uvs_;
  const std::vector<Uv>& uvs_;
  std::vector<std::array<int, 3>> neighbours_;  // per triangle, per edge k (corner k to k + 1); -1: none
};

}  // namespace

std::vector<Uv> continue_across_seams(const std::vector<Triangle>& triangles,
                                      const std::vector<std::array<int, 3>>& triangle_uvs, const std::vector<Uv>& uvs,
                                      const std::vector<int>& point_triangle, std::vector<Uv> values,
                                      const std::vector<int>& reference) {
  if (triangle_uvs.size() != triangles.size())
    throw InvalidInput(std::to_string(triangle_uvs.size()) + " triangles of texture coordinates for " +
                       std::to_string(triangles.size()) + " triangles");
  if (point_triangle.size() != values.size() || reference.size() != values.size())
    throw InvalidInput(std::to_string(values.size()) + " values for " + std::to_string(point_triangle.size()) +
                       " points and " + std::to_string(reference.size()) + " references");
  for (const auto& corners : triangle_uvs)
    for (int c : corners)
      if (c < 0 || std::size_t(c) >= uvs.size())
        throw InvalidInput("texture coordinate " + std::to_string(c) + " out of range (" + std::to_string(uvs.size()) +
                           ")");
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (point_triangle[i] < 0 || std::size_t(point_triangle[i]) >= triangles.size())
      throw InvalidInput("point " + std::to_string(i) + " lies on triangle " + std::to_string(point_triangle[i]) +
                         " of " + std::to_string(triangles.size()));
    if (reference[i] < 0 || std::size_t(reference[i]) >= values.size())
      throw InvalidInput("point " + std::to_string(i) + " refers to point " + std::to_string(reference[i]) + " of " +
                         std::to_string(values.size()));
  }
  const Charts charts(triangles, triangle_uvs, uvs);
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = charts.between(point_triangle[i], point_triangle[reference[i]]).apply(values[i]);
  return values;
}

ObjAttributes transfer_obj_attributes(const TriangleMesh& source, const ObjAttributes& source_attributes,
                                      const TriangleMesh& target, const IntersurfaceResult& map) {
  if (map.a_to_b.size() != target.vertices.size())
    throw InvalidInput("the map has " + std::to_string(map.a_to_b.size()) + " vertex images for " +
                       std::to_string(target.vertices.size()) + " target vertices");
  ObjAttributes result;
  if (!source_attributes.colors.empty())
    result.colors = interpolate_vertex_values<3>(source, source_attributes.colors, map.a_to_b);
  if (source_attributes.triangle_uvs.empty()) return result;
  if (source_attributes.triangle_uvs.size() != source.triangles.size())
    throw InvalidInput(std::to_string(source_attributes.triangle_uvs.size()) +
                       " triangles of texture coordinates for " + std::to_string(source.triangles.size()) +
                       " source triangles");
  if (map.a_corners_to_b.size() != 3 * target.triangles.size())
    throw InvalidInput("the map has " + std::to_string(map.a_corners_to_b.size()) + " corner images for " +
                       std::to_string(3 * target.triangles.size()) + " target corners (compute it with corner_images)");
  std::vector<int> point_triangle(map.a_corners_to_b.size()), reference(map.a_corners_to_b.size());
  for (std::size_t i = 0; i < point_triangle.size(); ++i)
    point_triangle[i] = map.a_corners_to_b[i].triangle, reference[i] = int(i - i % 3);  // each triangle's first corner
  const std::vector<std::array<double, 2>> uvs = continue_across_seams(
      source.triangles, source_attributes.triangle_uvs, source_attributes.uvs, point_triangle,
      interpolate_corner_values<2>(source_attributes.triangle_uvs, source_attributes.uvs, map.a_corners_to_b),
      reference);
  std::map<std::tuple<int, double, double>, int> shared;  // (vertex, u, v) -> index: one vt where corners agree
  result.triangle_uvs.resize(target.triangles.size());
  for (std::size_t t = 0; t < target.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::array<double, 2>& uv = uvs[3 * t + k];
      const auto [it, added] =
          shared.emplace(std::make_tuple(target.triangles[t][k], uv[0], uv[1]), int(result.uvs.size()));
      if (added) result.uvs.push_back(uv);
      result.triangle_uvs[t][k] = it->second;
    }
  return result;
}

}  // namespace cmaps
