#include "intersurface/patch_locator.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

const double kHeight = std::sqrt(3.0) / 2;  // of the canonical triangle (0, 0), (1, 0), (1/2, kHeight)

}  // namespace

namespace {

std::vector<std::array<Vec2, 3>> laid_out(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv,
                                          const std::vector<int>& faces) {
  std::vector<std::array<Vec2, 3>> corners;
  corners.reserve(faces.size());
  for (int f : faces) {
    const Triangle& t = side.mesh.triangles()[f];
    corners.push_back({uv.at(t[0]), uv.at(t[1]), uv.at(t[2])});
  }
  return corners;
}

}  // namespace

PatchLocator::PatchLocator(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv,
                           const std::vector<int>& faces)
    : PatchLocator(faces, laid_out(side, uv, faces)) {}

PatchLocator::PatchLocator(std::vector<int> faces, std::vector<std::array<Vec2, 3>> corners)
    : faces_(std::move(faces)), corners_(std::move(corners)) {
  cells_ = std::max(1, int(std::sqrt(double(faces_.size()))));
  buckets_.resize(cells_ * cells_);
  for (int i = 0; i < int(faces_.size()); ++i) {
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
  const auto corners = [&](int i, std::array<Vec2, 3>& c) { c = corners_[i]; };
  Holder best;
  const std::vector<int>& bucket = buckets_[y * cells_ + x];
  find_holder(p, bucket.begin(), bucket.end(), corners, best);
  if (best.score < -1e-9) {
    std::vector<int> all(faces_.size());
    std::iota(all.begin(), all.end(), 0);
    find_holder(p, all.begin(), all.end(), corners, best);
  }
  if (best.face < 0) throw Error("internal error: point outside every patch triangle");
  double sum = 0;
  for (double& w : best.weights) sum += (w = std::max(0.0, w));
  for (double& w : best.weights) w = sum > 0 ? w / sum : 1.0 / 3;
  return {faces_[best.face], best.weights};
}

std::pair<int, int> PatchLocator::cell(const Vec2& p) const {
  const auto clamp = [&](double t) { return std::clamp(int(t * cells_), 0, cells_ - 1); };
  return {clamp(p.x()), clamp(p.y() / kHeight)};
}

}  // namespace cmaps
