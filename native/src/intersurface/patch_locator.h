// Point location among one patch's triangles in its canonical triangle: a
// grid of buckets over the triangles' bounding boxes. Any triangles of a side
// laid out inside the unit square will do (corner_points: the refined faces of
// one input triangle in a chart of it).
#pragma once
#include <array>
#include <unordered_map>
#include <utility>
#include <vector>

#include "intersurface/patch_parameterization.h"

namespace cmaps {

// A point this far inside one triangle of an embedding (in barycentric
// weight) is inside no other: a search for the triangle holding it can stop.
constexpr double kSurelyInside = 1e-12;

class PatchLocator {
 public:
  // `faces`: the patch's triangles of `side`, `uv` their corners' canonical points.
  PatchLocator(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces);

  // The triangle holding p (the one it is least outside of, for points a
  // rounding error off the patch) and p's barycentric weights there, clamped
  // to the triangle and normalized.
  std::pair<int, std::array<double, 3>> locate(const Vec2& p) const;

 private:
  std::pair<int, int> cell(const Vec2& p) const;

  std::vector<int> faces_;
  std::vector<std::array<Vec2, 3>> corners_;  // per entry of faces_
  int cells_ = 1;
  std::vector<std::vector<int>> buckets_;  // entries of faces_
};

}  // namespace cmaps
