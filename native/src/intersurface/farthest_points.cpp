#include "intersurface/farthest_points.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

namespace cmaps {

int farthest_from_centroid(const TriangleMesh& mesh) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) centroid += v;
  centroid /= double(mesh.vertices.size());
  int best = 0;
  for (int v = 1; v < int(mesh.vertices.size()); ++v)
    if ((mesh.vertices[v] - centroid).squaredNorm() > (mesh.vertices[best] - centroid).squaredNorm()) best = v;
  return best;
}

Spread::Spread(const TriangleMesh& mesh, bool along_edges)
    : mesh_(mesh), distance_(mesh.vertices.size(), std::numeric_limits<double>::infinity()) {
  if (!along_edges) return;
  neighbours_.resize(mesh.vertices.size());
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      neighbours_[t[k]].push_back(t[(k + 1) % 3]), neighbours_[t[(k + 1) % 3]].push_back(t[k]);
}

void Spread::reach_from(int seed) {
  if (neighbours_.empty()) {
    for (std::size_t v = 0; v < distance_.size(); ++v)
      distance_[v] = std::min(distance_[v], (mesh_.vertices[v] - mesh_.vertices[seed]).squaredNorm());
    return;
  }
  // Dijkstra from the seed, stopping where an earlier seed is nearer.
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  distance_[seed] = 0;
  queue.push({0, seed});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance_[v]) continue;
    for (int w : neighbours_[v]) {
      const double through = d + (mesh_.vertices[w] - mesh_.vertices[v]).norm();
      if (through < distance_[w]) distance_[w] = through, queue.push({through, w});
    }
  }
}

int Spread::next(const std::vector<int>& seeds) {
  for (; taken_ < seeds.size(); ++taken_) reach_from(seeds[taken_]);
  const auto far = std::max_element(distance_.begin(), distance_.end(), [](double x, double y) {
    return (std::isfinite(x) ? x : -1) < (std::isfinite(y) ? y : -1);
  });
  return std::isfinite(*far) && *far > 0 ? int(far - distance_.begin()) : -1;
}

int spread_vertex(const TriangleMesh& mesh, int start) {
  std::vector<int> seeds{farthest_from_centroid(mesh)};
  Spread spread(mesh, /*along_edges=*/false);
  for (int k = 0, v = 0; k < start && (v = spread.next(seeds)) >= 0; ++k) seeds.push_back(v);
  return seeds.back();
}

}  // namespace cmaps
