#include "intersurface/patch_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

const double kHeight = std::sqrt(3.0) / 2;  // of the canonical triangle (0, 0), (1, 0), (1/2, kHeight)

// How far past a cell a triangle may reach and still be listed in it: a point
// a rounding error outside a cell may be placed in it.
constexpr double kCellSlack = 1e-9;
// Cells across the root square per square root of the triangle count.
constexpr int kCellsPerRootFace = 2;

// The smallest and largest x of triangle c between heights lo and hi (lo <= y
// <= hi); empty (min > max) when it does not reach there.
std::pair<double, double> x_range(const std::array<Vec2, 3>& c, double lo, double hi) {
  double min = std::numeric_limits<double>::infinity(), max = -min;
  const auto take = [&](double x) { min = std::min(min, x), max = std::max(max, x); };
  for (int k = 0; k < 3; ++k) {
    const Vec2 &a = c[k], &b = c[(k + 1) % 3];
    if (a.y() >= lo && a.y() <= hi) take(a.x());
    for (double level : {lo, hi})
      if ((a.y() - level) * (b.y() - level) < 0) take(a.x() + (level - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
  }
  return {min, max};
}

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
  cells_ = std::max(1, int(kCellsPerRootFace * std::sqrt(double(faces_.size()))));
  // Each triangle is listed in the cells it meets, row by row (not in every
  // cell of its bounding box: the embeddings are full of long thin triangles).
  // The outermost rows and columns reach to infinity, as cell() clamps.
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<std::pair<int, int>> listed;  // (cell, entry), entries increasing
  for (int i = 0; i < int(faces_.size()); ++i) {
    const auto& c = corners_[i];
    const int y0 = cell(c[0].cwiseMin(c[1]).cwiseMin(c[2])).second;
    const int y1 = cell(c[0].cwiseMax(c[1]).cwiseMax(c[2])).second;
    for (int y = y0; y <= y1; ++y) {
      const double lo = y == 0 ? -infinity : y * kHeight / cells_ - kCellSlack;
      const double hi = y == cells_ - 1 ? infinity : (y + 1) * kHeight / cells_ + kCellSlack;
      const auto [left, right] = x_range(c, lo, hi);
      if (left > right) continue;
      const int x1 = cell(Vec2(right + kCellSlack, 0)).first;
      for (int x = cell(Vec2(left - kCellSlack, 0)).first; x <= x1; ++x) listed.emplace_back(y * cells_ + x, i);
    }
  }
  // Counting sort by cell; each cell keeps its entries in increasing order.
  bucket_start_.assign(cells_ * cells_ + 1, 0);
  for (const auto& [k, i] : listed) ++bucket_start_[k + 1];
  std::partial_sum(bucket_start_.begin(), bucket_start_.end(), bucket_start_.begin());
  bucket_entries_.resize(listed.size());
  std::vector<int> next(bucket_start_.begin(), bucket_start_.end() - 1);
  for (const auto& [k, i] : listed) bucket_entries_[next[k]++] = i;
  entry_of_face_.reserve(faces_.size());
  for (int i = 0; i < int(faces_.size()); ++i) entry_of_face_.emplace_back(faces_[i], i);
  std::sort(entry_of_face_.begin(), entry_of_face_.end());
}

std::pair<int, std::array<double, 3>> PatchLocator::locate(const Vec2& p, int hint) const {
  const auto it = std::lower_bound(entry_of_face_.begin(), entry_of_face_.end(), std::pair<int, int>(hint, -1));
  if (it != entry_of_face_.end() && it->first == hint) {
    const auto& c = corners_[it->second];
    const std::array<double, 3> w = barycentric(p, c[0], c[1], c[2]);
    if (std::min({w[0], w[1], w[2]}) > kSurelyInside) return normalized(hint, w);
  }
  return locate(p);
}

std::pair<int, std::array<double, 3>> PatchLocator::locate(const Vec2& p) const {
  const auto [x, y] = cell(p);
  const auto corners = [&](int i, std::array<Vec2, 3>& c) { c = corners_[i]; };
  Holder best;
  const int at = y * cells_ + x;
  find_holder(p, bucket_entries_.begin() + bucket_start_[at], bucket_entries_.begin() + bucket_start_[at + 1], corners,
              best);
  if (best.score < -1e-9) {
    std::vector<int> all(faces_.size());
    std::iota(all.begin(), all.end(), 0);
    find_holder(p, all.begin(), all.end(), corners, best);
  }
  if (best.face < 0) throw Error("internal error: point outside every patch triangle");
  return normalized(faces_[best.face], best.weights);
}

// Weights clamped to the triangle and summing to 1.
std::pair<int, std::array<double, 3>> PatchLocator::normalized(int face, std::array<double, 3> weights) {
  double sum = 0;
  for (double& w : weights) sum += (w = std::max(0.0, w));
  for (double& w : weights) w = sum > 0 ? w / sum : 1.0 / 3;
  return {face, weights};
}

std::pair<int, int> PatchLocator::cell(const Vec2& p) const {
  const auto clamp = [&](double t) { return std::clamp(int(t * cells_), 0, cells_ - 1); };
  return {clamp(p.x()), clamp(p.y() / kHeight)};
}

}  // namespace cmaps
