#include "intersurface/patch_locator.h"

#include <algorithm>
#include <cmath>

#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

const double kHeight = std::sqrt(3.0) / 2;  // of the canonical triangle (0, 0), (1, 0), (1/2, kHeight)

// Barycentric coordinates of p in the 2D triangle c.
std::array<double, 3> barycentric(const Vec2& p, const std::array<Vec2, 3>& c) {
  const Vec2 b = c[1] - c[0], d = c[2] - c[0], q = p - c[0];
  const double det = b.x() * d.y() - b.y() * d.x();
  if (std::abs(det) < 1e-300) return {-1, -1, -1};
  const double s = (q.x() * d.y() - q.y() * d.x()) / det;
  const double t = (b.x() * q.y() - b.y() * q.x()) / det;
  return {1 - s - t, s, t};
}

}  // namespace

PatchLocator::PatchLocator(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv,
                           const std::vector<int>& faces)
    : faces_(faces) {
  cells_ = std::max(1, int(std::sqrt(double(faces.size()))));
  buckets_.resize(cells_ * cells_);
  corners_.reserve(faces.size());
  for (int i = 0; i < int(faces.size()); ++i) {
    const Triangle& t = side.mesh.triangles()[faces[i]];
    corners_.push_back({uv.at(t[0]), uv.at(t[1]), uv.at(t[2])});
    const Vec2 lo = corners_[i][0].cwiseMin(corners_[i][1]).cwiseMin(corners_[i][2]);
    const Vec2 hi = corners_[i][0].cwiseMax(corners_[i][1]).cwiseMax(corners_[i][2]);
    const auto [x0, y0] = cell(lo);
    const auto [x1, y1] = cell(hi);
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y) buckets_[y * cells_ + x].push_back(i);
  }
}

std::pair<int, std::array<double, 3>> PatchLocator::locate(const Vec2& p) const {
  const auto [x, y] = cell(p);
  int best = -1;
  std::array<double, 3> weights{};
  double score = -1e300;
  const auto test = [&](int i) {
    const auto w = barycentric(p, corners_[i]);
    const double m = std::min({w[0], w[1], w[2]});
    if (m > score) score = m, best = i, weights = w;
  };
  for (auto i = buckets_[y * cells_ + x].begin(); i != buckets_[y * cells_ + x].end() && score <= kSurelyInside; ++i)
    test(*i);
  if (score < -1e-9)
    for (int i = 0; i < int(faces_.size()); ++i) test(i);
  if (best < 0) throw Error("internal error: point outside every patch triangle");
  double sum = 0;
  for (double& w : weights) sum += (w = std::max(0.0, w));
  for (double& w : weights) w = sum > 0 ? w / sum : 1.0 / 3;
  return {faces_[best], weights};
}

std::pair<int, int> PatchLocator::cell(const Vec2& p) const {
  const auto clamp = [&](double t) { return std::clamp(int(t * cells_), 0, cells_ - 1); };
  return {clamp(p.x()), clamp(p.y() / kHeight)};
}

}  // namespace cmaps
