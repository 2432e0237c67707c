#include "intersurface/patch_embedding.h"

#include <cmath>

#include "consistent_maps/errors.h"

namespace cmaps {

PatchEmbedding::PatchEmbedding(const PartitionSide& side, const std::vector<int>& faces,
                               std::unordered_map<int, Vec2>& uv)
    : side_(side), faces_(faces), uv_(uv) {
  for (int f : faces)
    for (int v : side.mesh.triangles()[f])
      if (!uv.count(v) && !index_.count(v)) index_.emplace(v, int(index_.size()));
}

PatchEmbedding::Weights PatchEmbedding::mean_value_weights() const {
  Weights weight(index_.size());
  for (int f : faces_) {
    const Triangle& t = side_.mesh.triangles()[f];
    for (int k = 0; k < 3; ++k) {
      const auto it = index_.find(t[k]);
      if (it == index_.end()) continue;
      const Vec3 &p = side_.mesh.position(t[k]), &q = side_.mesh.position(t[(k + 1) % 3]),
                 &r = side_.mesh.position(t[(k + 2) % 3]);
      const double lq = (q - p).norm(), lr = (r - p).norm();
      const double angle = std::atan2((q - p).cross(r - p).norm(), (q - p).dot(r - p));
      const double half = std::tan(angle / 2);
      for (const auto& [v, l] : {std::pair<int, double>{t[(k + 1) % 3], lq}, {t[(k + 2) % 3], lr}}) {
        const double w = half / l;
        weight[it->second][v] += std::isfinite(w) && w > 0 ? w : 1e-12;
      }
    }
  }
  return weight;
}

void PatchEmbedding::solve(const Weights& weight) {
  const int n = int(index_.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  for (const auto& [v, i] : index_) {
    double total = 0;
    for (const auto& [u, w] : weight[i]) {
      total += w;
      const auto j = index_.find(u);
      if (j != index_.end()) entries.emplace_back(i, j->second, -w);
      else rhs.row(i) += w * uv_.at(u).transpose();
    }
    entries.emplace_back(i, i, total);
  }
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  // Every solve's weights are positive on the same edges: one ordering serves them all.
  if (!analyzed_) solver_.analyzePattern(matrix), analyzed_ = true;
  solver_.factorize(matrix);
  if (solver_.info() != Eigen::Success) throw Error("internal error: a patch parameterization is singular");
  const Eigen::MatrixXd x = solver_.solve(rhs);
  for (const auto& [v, i] : index_) uv_[v] = x.row(i).transpose();
}

}  // namespace cmaps
