// The base mesh of a consistent partition as one flat surface with cone
// points at the base vertices: every base triangle is the canonical
// equilateral triangle (patch_parameterization.h), and the two triangles
// beside a base edge are glued by the rotation and translation that take
// the edge's canonical position in one onto its position in the other (the
// same fraction of the path at the same point: the patch embeddings agree
// along paths). A point near a base triangle's side can thus be carried into
// the neighbour's plane, and a small region around it developed flat into
// one triangle's plane, as long as it holds no base vertex inside.
#pragma once
#include <array>
#include <complex>
#include <vector>

#include "intersurface/patch_parameterization.h"

namespace cmaps {

class BaseComplex {
 public:
  // Base triangles whose patch is a hole's fan (fan[t] != 0) glue to nothing:
  // nothing crosses into a hole or out of it.
  BaseComplex(const ConsistentPartition& partition, const std::vector<char>& fan);

  int triangles() const { return int(glue_.size()); }

  // The triangle across side k (corner k to corner k + 1) of t; -1 when none.
  int neighbour(int t, int k) const { return glue_[t][k].neighbour; }
  // A point of that neighbour's canonical plane in t's plane.
  Vec2 from_neighbour(int t, int k, const Vec2& p) const;
  // A point of t's plane in the plane of the neighbour across side k.
  Vec2 to_neighbour(int t, int k, const Vec2& p) const;

  // The copy of `p` (a point of triangle `from`) in t's plane nearest `near`:
  // p itself when from == t, else carried across one side of t, or across a
  // side of a neighbour of t and then one of t's. False when `from` is
  // farther than that.
  bool develop(int from, const Vec2& p, int t, const Vec2& near, Vec2& result) const;

  // The copy of base vertex `vertex` in t's plane nearest `near`: a corner of
  // t or of a neighbour; false when neither has it.
  bool develop_corner(int vertex, int t, const Vec2& near, Vec2& result) const;

  // The triangle holding `p` of t's plane: t, or the neighbour across one of
  // its sides (with p in that neighbour's plane); false when neither.
  bool home_of(int t, const Vec2& p, int& home, Vec2& at) const;

 private:
  struct Glue {
    int neighbour = -1;
    std::complex<double> a{1, 0}, b{0, 0};  // neighbour's plane -> this one: z -> a z + b
  };
  std::vector<std::array<Glue, 3>> glue_;
  std::vector<std::array<int, 3>> corners_;  // per base triangle: its base vertices
};

}  // namespace cmaps
