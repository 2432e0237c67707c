// One side of a consistent partition embedded on the base mesh glued flat
// (base_complex.h): each vertex at a canonical point of one base triangle,
// its home. The patch embeddings give one (a path vertex takes the point of
// one patch beside it; the other patch's agrees up to rounding); after the
// side's vertices crossed paths (cross_patch_optimization.h) its triangles
// straddle base edges and only this form holds the embedding. Either side
// can then be the fixed one the other moves against: its points are located
// among its triangles developed into each base triangle's plane.
//
// Invariant: every triangle develops into the plane of its corners (no
// corner farther than two base triangles from another) and turns like the
// whole embedding there; base vertices sit at their base triangles'
// corners, wherever their home is.
#pragma once
#include <array>
#include <unordered_map>
#include <vector>

#include "intersurface/base_complex.h"
#include "intersurface/patch_locator.h"

namespace cmaps {

struct GluedEmbedding {
  std::vector<int> home;    // per vertex: its base triangle
  std::vector<Vec2> point;  // per vertex: its canonical point there
  // Per base triangle that is a hole's fan: its vertices' points (a rim
  // vertex's home is a surface patch; fans glue to nothing and never move).
  std::vector<std::unordered_map<int, Vec2>> fan_uv;
};

// The side's patch embeddings as one glued embedding: each vertex in a
// surface patch beside it (a hole's fan only when it has no other).
GluedEmbedding glue_patches(const PartitionSide& side, const PatchParameterization& uv);

class GluedSide {
 public:
  GluedSide(const PartitionSide& side, const BaseComplex& base, GluedEmbedding embedding);

  const PartitionSide& side() const { return side_; }
  const GluedEmbedding& embedding() const { return embedding_; }
  int home(int v) const { return embedding_.home[v]; }
  const Vec2& point(int v) const { return embedding_.point[v]; }
  int base_vertex(int v) const { return base_vertex_[v]; }
  void move(int v, int home, const Vec2& point) { embedding_.home[v] = home, embedding_.point[v] = point; }

  // Vertex u in base triangle t's plane, the copy nearest `near`.
  bool develop(int u, int t, const Vec2& near, Vec2& result) const;
  // Triangle f developed into the plane of its corner of largest weight
  // that is no base vertex (base vertices lie in several base triangles);
  // that plane, or -1 when a corner cannot be developed.
  int develop_triangle(int f, const std::array<double, 3>& weights, std::array<Vec2, 3>& corners) const;
  // A point of triangle f (weights) as a base triangle and its canonical
  // point there; false short of a broken embedding.
  bool canonical_point(int f, const std::array<double, 3>& weights, int& home, Vec2& point) const;

  // Point location: per base triangle, the side's triangles reaching into
  // it, developed into its plane. Built by `locators`, for a fixed side.
  std::vector<PatchLocator> locators() const;

 private:
  const PartitionSide& side_;
  const BaseComplex& base_;
  GluedEmbedding embedding_;
  std::vector<int> base_vertex_;  // per vertex: its base vertex, -1 for none
};

}  // namespace cmaps
