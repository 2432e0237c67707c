#include "intersurface/patch_parameterization.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <string>

#include "common/parallel_for.h"
#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

const Vec2 kCorner[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, std::sqrt(3.0) / 2)};

// Splits every non-path edge whose ends both lie on paths, keeping `patch`
// (per triangle) in step with the new triangles.
void split_chords(PartitionSide& side) {
  std::vector<char> on_path(side.mesh.vertex_count(), 0);
  std::vector<char> path_edge(side.mesh.edge_count(), 0);
  for (const auto& path : side.paths) {
    for (int v : path) on_path[v] = 1;
    for (size_t i = 0; i + 1 < path.size(); ++i) path_edge[side.mesh.edge(path[i], path[i + 1])] = 1;
  }
  const int edges = side.mesh.edge_count();
  for (int e = 0; e < edges; ++e) {
    const auto [u, w] = side.mesh.edge_vertices(e);
    if (u < 0 || path_edge[e] || !on_path[u] || !on_path[w]) continue;
    const auto faces = side.mesh.edge_faces(e);
    side.mesh.split_edge(e);
    side.patch.push_back(side.patch[faces[0]]);
    side.patch.push_back(side.patch[faces[1]]);
  }
}

// Canonical points of one patch: its boundary by arc length, its interior
// by mean-value weights.
std::unordered_map<int, Vec2> parameterize(const PartitionSide& side, const BaseTriangle& base,
                                           const std::vector<int>& faces) {
  std::unordered_map<int, Vec2> uv;
  for (int k = 0; k < 3; ++k) {
    std::vector<int> path = side.paths[base.edges[k]];
    if (base.reversed[k]) std::reverse(path.begin(), path.end());
    std::vector<double> at{0};
    for (size_t i = 1; i < path.size(); ++i)
      at.push_back(at.back() + (side.mesh.position(path[i]) - side.mesh.position(path[i - 1])).norm());
    for (size_t i = 0; i < path.size(); ++i) {
      const double t = at.back() > 0 ? at[i] / at.back() : double(i) / (path.size() - 1);
      uv[path[i]] = (1 - t) * kCorner[k] + t * kCorner[(k + 1) % 3];
    }
  }
  std::unordered_map<int, int> index;  // interior vertex -> unknown
  for (int f : faces)
    for (int v : side.mesh.triangles()[f])
      if (!uv.count(v) && !index.count(v)) index.emplace(v, int(index.size()));
  const int n = int(index.size());
  if (n == 0) return uv;

  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  std::vector<std::unordered_map<int, double>> weight(n);
  for (int f : faces) {
    const Triangle& t = side.mesh.triangles()[f];
    for (int k = 0; k < 3; ++k) {
      const auto it = index.find(t[k]);
      if (it == index.end()) continue;
      const Vec3 &p = side.mesh.position(t[k]), &q = side.mesh.position(t[(k + 1) % 3]),
                 &r = side.mesh.position(t[(k + 2) % 3]);
      const double lq = (q - p).norm(), lr = (r - p).norm();
      const double angle = std::atan2((q - p).cross(r - p).norm(), (q - p).dot(r - p));
      const double half = std::tan(angle / 2);
      for (const auto& [v, l] : {std::pair<int, double>{t[(k + 1) % 3], lq}, {t[(k + 2) % 3], lr}}) {
        const double w = half / l;
        weight[it->second][v] += std::isfinite(w) && w > 0 ? w : 1e-12;
      }
    }
  }
  for (const auto& [v, i] : index) {
    double total = 0;
    for (const auto& [u, w] : weight[i]) {
      total += w;
      const auto j = index.find(u);
      if (j != index.end()) entries.emplace_back(i, j->second, -w);
      else rhs.row(i) += w * uv.at(u).transpose();
    }
    entries.emplace_back(i, i, total);
  }
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
  solver.compute(matrix);
  if (solver.info() != Eigen::Success) throw Error("internal error: a patch parameterization is singular");
  const Eigen::MatrixXd x = solver.solve(rhs);
  for (const auto& [v, i] : index) uv[v] = x.row(i).transpose();
  return uv;
}

// Barycentric coordinates of p in the 2D triangle (a, b, c).
std::array<double, 3> barycentric(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double det = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (std::abs(det) < 1e-300) return {-1, -1, -1};
  const double s = ((p - a).x() * (c - a).y() - (p - a).y() * (c - a).x()) / det;
  const double t = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / det;
  return {1 - s - t, s, t};
}

// Point location among one patch's triangles in the canonical triangle (a grid of buckets).
class PatchLocator {
 public:
  PatchLocator(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces)
      : side_(side), uv_(uv), faces_(faces) {
    cells_ = std::max(1, int(std::sqrt(double(faces.size()))));
    buckets_.resize(cells_ * cells_);
    for (int f : faces) {
      Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
      for (int v : side.mesh.triangles()[f]) lo = lo.cwiseMin(uv.at(v)), hi = hi.cwiseMax(uv.at(v));
      const auto [x0, y0] = cell(lo);
      const auto [x1, y1] = cell(hi);
      for (int x = x0; x <= x1; ++x)
        for (int y = y0; y <= y1; ++y) buckets_[y * cells_ + x].push_back(f);
    }
  }

  // The triangle holding p (the one it is least outside of) and p's barycentric weights there.
  std::pair<int, std::array<double, 3>> locate(const Vec2& p) const {
    const auto [x, y] = cell(p);
    std::pair<int, std::array<double, 3>> best{-1, {}};
    double score = -1e300;
    const auto test = [&](int f) {
      const Triangle& t = side_.mesh.triangles()[f];
      const auto w = barycentric(p, uv_.at(t[0]), uv_.at(t[1]), uv_.at(t[2]));
      const double m = std::min({w[0], w[1], w[2]});
      if (m > score) score = m, best = {f, w};
    };
    for (int f : buckets_[y * cells_ + x]) test(f);
    if (score < -1e-9)
      for (int f : faces_) test(f);
    if (best.first < 0) throw Error("internal error: point outside every patch triangle");
    double sum = 0;
    for (double& w : best.second) sum += (w = std::max(0.0, w));
    for (double& w : best.second) w = sum > 0 ? w / sum : 1.0 / 3;
    return best;
  }

 private:
  std::pair<int, int> cell(const Vec2& p) const {
    const auto clamp = [&](double t) { return std::clamp(int(t * cells_), 0, cells_ - 1); };
    return {clamp(p.x()), clamp(p.y() / kCorner[2].y())};
  }

  const PartitionSide& side_;
  const std::unordered_map<int, Vec2>& uv_;
  const std::vector<int>& faces_;
  int cells_ = 1;
  std::vector<std::vector<int>> buckets_;
};

// A point of the refined target (triangle, weights) on its input triangle.
InputLocation to_input(const PartitionSide& side, const TriangleMesh& input, int face, const std::array<double, 3>& w) {
  InputLocation p;
  p.triangle = side.mesh.input_triangle(face);
  const Triangle& corners = input.triangles[p.triangle];
  double stray = 0;
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const InputPoint& origin = side.mesh.surface_point(side.mesh.triangles()[face][k]);
    for (int j = 0; j < 3; ++j) {
      const int v = origin.vertices[j];
      if (v < 0) continue;
      const double weight = w[k] * origin.weights[j];
      x += weight * input.vertices[v];
      const int slot = int(std::find(corners.begin(), corners.end(), v) - corners.begin());
      if (slot < 3) p.barycentric[slot] += weight;
      else stray += std::abs(weight);
    }
  }
  if (stray > 1e-12) {  // never, up to the refinement's bookkeeping: project onto the triangle
    const Vec3 &a = input.vertices[corners[0]], e1 = input.vertices[corners[1]] - a, e2 = input.vertices[corners[2]] - a;
    const double aa = e1.dot(e1), ab = e1.dot(e2), bb = e2.dot(e2), det = aa * bb - ab * ab;
    const Vec3 d = x - a;
    const double s = det > 0 ? (bb * d.dot(e1) - ab * d.dot(e2)) / det : 0;
    const double t = det > 0 ? (aa * d.dot(e2) - ab * d.dot(e1)) / det : 0;
    p.barycentric = {1 - s - t, s, t};
  }
  double sum = 0;
  for (double& b : p.barycentric) sum += (b = std::max(0.0, b));
  for (double& b : p.barycentric) b = sum > 0 ? b / sum : 1.0 / 3;
  return p;
}

std::vector<std::vector<int>> faces_by_patch(const PartitionSide& side, int patches) {
  std::vector<std::vector<int>> faces(patches);
  for (int f = 0; f < int(side.patch.size()); ++f) faces[side.patch[f]].push_back(f);
  return faces;
}

}  // namespace

PatchParameterization parameterize_patches(PartitionSide& side, const ConsistentPartition& partition) {
  split_chords(side);
  const int patches = int(partition.triangles.size());
  const std::vector<std::vector<int>> faces = faces_by_patch(side, patches);
  PatchParameterization result;
  result.uv.resize(patches);
  parallel_for(patches, 2, [&](int t) { result.uv[t] = parameterize(side, partition.triangles[t], faces[t]); });
  return result;
}

std::vector<InputLocation> map_vertices(const PartitionSide& source, const PatchParameterization& source_uv,
                                        const PartitionSide& target, const PatchParameterization& target_uv,
                                        const TriangleMesh& target_input, int threads) {
  const int patches = int(target_uv.uv.size());
  const std::vector<std::vector<int>> faces = faces_by_patch(target, patches);
  std::vector<PatchLocator> locators;
  locators.reserve(patches);
  for (int t = 0; t < patches; ++t) locators.emplace_back(target, target_uv.uv[t], faces[t]);

  const int n = source.mesh.input_vertex_count();
  std::vector<InputLocation> image(n);
  parallel_for(n, threads, [&](int v) {
    const int t = source.patch[source.mesh.faces_of(v).front()];
    const auto [face, w] = locators[t].locate(source_uv.uv[t].at(v));
    image[v] = to_input(target, target_input, face, w);
  });

  // Features exactly onto their partners.
  std::vector<int> incident(target_input.vertices.size(), -1);
  for (int t = 0; t < int(target_input.triangles.size()); ++t)
    for (int v : target_input.triangles[t])
      if (incident[v] < 0) incident[v] = t;
  for (size_t f = 0; f < source.feature_vertex.size(); ++f) {
    const int from = source.feature_vertex[f], to = target.feature_vertex[f];
    if (from >= n || to >= target.mesh.input_vertex_count()) continue;
    InputLocation& p = image[from];
    p.triangle = incident[to];
    for (int j = 0; j < 3; ++j) p.barycentric[j] = target_input.triangles[p.triangle][j] == to ? 1 : 0;
  }
  return image;
}

}  // namespace cmaps
