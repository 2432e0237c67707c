// A convex-combination (Tutte-style) embedding of one patch's interior in its
// canonical triangle: every interior vertex at a positively weighted mean of
// its neighbours, the boundary fixed. Bijective for a disk with a convex
// boundary and no edge between two boundary vertices (Floater 2003), whatever
// the positive weights, so callers reweight freely and solve again.
#pragma once
#include <unordered_map>
#include <vector>

#include "common/diagonally_dominant_lu.h"
#include "intersurface/patch_parameterization.h"

namespace cmaps {

class PatchEmbedding {
 public:
  // Per interior vertex (rows in the order the constructor met them): neighbour -> weight.
  using Weights = std::vector<std::unordered_map<int, double>>;

  // `uv` holds the canonical points of the boundary (and only those, on
  // construction): every other vertex of `faces` is interior, and `solve`
  // writes its point there.
  PatchEmbedding(const PartitionSide& side, const std::vector<int>& faces, std::unordered_map<int, Vec2>& uv);

  bool empty() const { return index_.empty(); }

  // Mean-value weights (Floater 2003) of every interior vertex's neighbours.
  Weights mean_value_weights() const;

  // Every interior vertex at the weighted mean of its neighbours.
  void solve(const Weights& weight);

 private:
  const PartitionSide& side_;
  const std::vector<int>& faces_;
  std::unordered_map<int, Vec2>& uv_;
  std::unordered_map<int, int> index_;  // interior vertex -> unknown
  DiagonallyDominantLU solver_;
  bool analyzed_ = false;
};

}  // namespace cmaps
