// Point location among one patch's triangles in its canonical triangle: a
// grid of buckets, each listing the triangles that meet its cell (not every
// triangle whose bounding box does: the embeddings are full of long thin
// triangles, and the boxes covered a hundred times their area). Any triangles
// of a side laid out in the plane will do (corner_points: the refined faces
// of one input triangle in a chart of it).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "intersurface/patch_parameterization.h"

namespace cmaps {

// A point this far inside one triangle of an embedding (in barycentric
// weight) is inside no other: a search for the triangle holding it can stop.
constexpr double kSurelyInside = 1e-12;

// Barycentric coordinates of p in the 2D triangle (a, b, c); all -1 when degenerate.
inline std::array<double, 3> barycentric(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 e = b - a, d = c - a, q = p - a;
  const double det = e.x() * d.y() - e.y() * d.x();
  if (std::abs(det) < 1e-300) return {-1, -1, -1};
  const double s = (q.x() * d.y() - q.y() * d.x()) / det, t = (e.x() * q.y() - e.y() * q.x()) / det;
  return {1 - s - t, s, t};
}

// The triangle of an embedding that a point lies least outside of: the
// largest smallest barycentric weight (`score`), the first of equals.
struct Holder {
  int face = -1;
  std::array<double, 3> weights{};
  double score = -std::numeric_limits<double>::infinity();
};

// Scans faces [first, last) in order, each laid out by corners(f, c), into
// `best`, until one surely holds p.
template <class Iterator, class Corners>
void find_holder(const Vec2& p, Iterator first, Iterator last, const Corners& corners, Holder& best) {
  for (; first != last && best.score <= kSurelyInside; ++first) {
    std::array<Vec2, 3> c;
    corners(*first, c);
    const std::array<double, 3> w = barycentric(p, c[0], c[1], c[2]);
    const double low = std::min({w[0], w[1], w[2]});
    if (low > best.score) best = {*first, w, low};
  }
}

class PatchLocator {
 public:
  // `faces`: the patch's triangles of `side`, `uv` their corners' canonical points.
  PatchLocator(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces);
  // `faces` laid out at `corners` (glued_side.h: a glued side's triangles reaching into one base triangle).
  PatchLocator(std::vector<int> faces, std::vector<std::array<Vec2, 3>> corners);

  // The triangle holding p (the one it is least outside of, for points a
  // rounding error off the patch) and p's barycentric weights there, clamped
  // to the triangle and normalized.
  std::pair<int, std::array<double, 3>> locate(const Vec2& p) const;
  // The same, first trying triangle `hint` (a face of the patch, or -1): a
  // point moved a little usually stays in its triangle, and a triangle that
  // surely holds p is the one the grid finds (the triangles do not overlap).
  std::pair<int, std::array<double, 3>> locate(const Vec2& p, int hint) const;

 private:
  std::pair<int, int> cell(const Vec2& p) const;
  static std::pair<int, std::array<double, 3>> normalized(int face, std::array<double, 3> weights);

  std::vector<int> faces_;
  std::vector<std::array<Vec2, 3>> corners_;  // per entry of faces_
  int cells_ = 1;
  // Entries of faces_ meeting each cell: cell k's are bucket_entries_[bucket_start_[k], bucket_start_[k + 1]).
  std::vector<int> bucket_start_, bucket_entries_;
  std::vector<std::pair<int, int>> entry_of_face_;  // (face, entry of faces_), sorted
};

}  // namespace cmaps
