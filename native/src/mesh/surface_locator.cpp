#include "consistent_maps/surface_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/parallel_for.h"
#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

constexpr int kLeafSize = 4;

struct Nearest {
  Vec3 point;
  std::array<double, 3> barycentric;
};

// The point of segment ab nearest p, as weights of a and b.
Nearest nearest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return {a + t * ab, {1 - t, t, 0}};
}

// The point of triangle abc nearest p, by the Voronoi regions of its
// corners, edges and face (Ericson, Real-Time Collision Detection, 5.1.5).
// A zero-area triangle is searched along its edges.
Nearest nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, {1, 0, 0}};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, {0, 1, 0}};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, {1 - v, v, 0}};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, {0, 0, 1}};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, {1 - w, 0, w}};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), {0, 1 - w, w}};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {  // degenerate: the nearest of the three edges
    Nearest best = nearest_on_segment(p, a, b);
    Nearest bc = nearest_on_segment(p, b, c), ca = nearest_on_segment(p, c, a);
    bc.barycentric = {0, bc.barycentric[0], bc.barycentric[1]};
    ca.barycentric = {ca.barycentric[1], 0, ca.barycentric[0]};
    for (const Nearest& n : {bc, ca})
      if ((n.point - p).squaredNorm() < (best.point - p).squaredNorm()) best = n;
    return best;
  }
  const double v = vb / sum, w = vc / sum;
  return {a + v * ab + w * ac, {1 - v - w, v, w}};
}

double box_distance2(const Vec3& p, const Vec3& low, const Vec3& high) {
  return (low - p).cwiseMax(p - high).cwiseMax(0.0).squaredNorm();
}

}  // namespace

SurfaceLocator::SurfaceLocator(std::vector<Vec3> vertices, std::vector<Triangle> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  if (triangles_.empty()) throw InvalidInput("a surface locator needs at least one triangle");
  for (std::size_t v = 0; v < vertices_.size(); ++v)
    if (!vertices_[v].allFinite())
      throw InvalidInput("vertex " + std::to_string(v) + " has a non-finite coordinate");
  const int n = int(vertices_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (int v : triangles_[t])
      if (v < 0 || v >= n)
        throw InvalidInput("triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                           " out of range (" + std::to_string(n) + " vertices)");
  std::vector<Vec3> centroids(triangles_.size());
  order_.resize(triangles_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const Triangle& f = triangles_[t];
    centroids[t] = (vertices_[f[0]] + vertices_[f[1]] + vertices_[f[2]]) / 3;
    order_[t] = int(t);
  }
  nodes_.reserve(2 * triangles_.size() / kLeafSize + 1);
  build(0, int(triangles_.size()), centroids);
}

int SurfaceLocator::build(int first, int count, std::vector<Vec3>& centroids) {
  const int index = int(nodes_.size());
  nodes_.emplace_back();
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  Vec3 centre_low = low, centre_high = high;
  for (int i = first; i < first + count; ++i) {
    for (int v : triangles_[order_[i]]) low = low.cwiseMin(vertices_[v]), high = high.cwiseMax(vertices_[v]);
    centre_low = centre_low.cwiseMin(centroids[order_[i]]), centre_high = centre_high.cwiseMax(centroids[order_[i]]);
  }
  nodes_[index].low = low, nodes_[index].high = high;
  if (count <= kLeafSize) {
    nodes_[index].first = first, nodes_[index].count = count;
    return index;
  }
  int axis = 0;
  (centre_high - centre_low).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int s, int t) { return centroids[s][axis] < centroids[t][axis]; });
  const int left = build(first, half, centroids);
  const int right = build(first + half, count - half, centroids);
  nodes_[index].children[0] = left, nodes_[index].children[1] = right;
  return index;
}

SurfaceLocation SurfaceLocator::locate(const Vec3& point) const {
  if (!point.allFinite()) throw InvalidInput("a surface locator cannot locate a non-finite point");
  SurfaceLocation best;
  double best2 = std::numeric_limits<double>::infinity();
  int stack[128];  // depth ~ log2(triangles / kLeafSize), two entries per level
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_distance2(point, node.low, node.high) >= best2) continue;
    if (node.children[0] < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const Triangle& f = triangles_[order_[i]];
        const Nearest n = nearest_on_triangle(point, vertices_[f[0]], vertices_[f[1]], vertices_[f[2]]);
        const double d2 = (n.point - point).squaredNorm();
        if (d2 < best2) best2 = d2, best.triangle = order_[i], best.barycentric = n.barycentric;
      }
      continue;
    }
    // The nearer child popped first.
    const int near = node.children[0], far = node.children[1];
    const bool swap = box_distance2(point, nodes_[far].low, nodes_[far].high) <
                      box_distance2(point, nodes_[near].low, nodes_[near].high);
    stack[top++] = swap ? near : far;
    stack[top++] = swap ? far : near;
  }
  best.distance = std::sqrt(best2);
  return best;
}

std::vector<SurfaceLocation> SurfaceLocator::locate_all(const std::vector<Vec3>& points, int threads) const {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw InvalidInput("point " + std::to_string(i) + " has a non-finite coordinate");
  std::vector<SurfaceLocation> result(points.size());
  parallel_for(points.size(), threads, [&](std::size_t i) { result[i] = locate(points[i]); }, 1024);
  return result;
}

}  // namespace cmaps
