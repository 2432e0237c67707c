// Flips that unfold a triangulation over two geometries at once: a quad
// split outside itself on one geometry is split along its other diagonal,
// and only when that folds fewer triangles over both.
#include <gtest/gtest.h>

#include "remesh/unfolding_flips.h"

namespace cmaps {
namespace {

// Two triangles sharing the edge 0 - 1; the quad runs 0, 3, 1, 2.
std::vector<Triangle> quad() { return {{0, 1, 2}, {1, 0, 3}}; }

const std::vector<Vec3> kUp(4, Vec3(0, 0, 1));
// A convex square: both diagonals split it into triangles facing up.
const std::vector<Vec3> kSquare{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 0}};
// A dart with its reflex corner at 2, below the diagonal 0 - 1: triangle (0, 1, 2) faces down.
const std::vector<Vec3> kDartAt2{{0, 0, 0}, {2, 2, 0}, {1.5, 0.5, 0}, {2, 0, 0}};
// Corner 3 above the line through 1 and 2: the split 0 - 1 faces up, the split 2 - 3 folds (3, 1, 2).
const std::vector<Vec3> kOtherSplitFolds{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1.5, 1.2, 0}};

int folded(const std::vector<Triangle>& triangles, const std::vector<FoldGeometry>& geometries) {
  int count = 0;
  for (const Triangle& t : triangles)
    for (const FoldGeometry& g : geometries) count += folds(g, t);
  return count;
}

TEST(UnfoldingFlips, AQuadSplitOutsideItselfIsSplitAlongItsOtherDiagonal) {
  std::vector<Triangle> triangles = quad();
  const std::vector<FoldGeometry> geometries{{kSquare, kUp}, {kDartAt2, kUp}};
  ASSERT_EQ(folded(triangles, geometries), 1);
  EXPECT_EQ(unfold_by_flips(triangles, {1, 1}, geometries), 1);
  EXPECT_EQ(folded(triangles, geometries), 0);
  EXPECT_EQ(triangles, (std::vector<Triangle>{{0, 3, 2}, {3, 1, 2}}));
}

TEST(UnfoldingFlips, NoFlipMovesAFoldFromOneGeometryToTheOther) {
  std::vector<Triangle> triangles = quad();
  const std::vector<FoldGeometry> geometries{{kOtherSplitFolds, kUp}, {kDartAt2, kUp}};
  ASSERT_EQ(folded(triangles, geometries), 1);  // the split 0 - 1 folds on the second, 2 - 3 would on the first
  EXPECT_EQ(unfold_by_flips(triangles, {1, 1}, geometries), 0);
  EXPECT_EQ(triangles, quad());
}

TEST(UnfoldingFlips, ATriangleThatMayNotFlipKeepsItsEdges) {
  std::vector<Triangle> triangles = quad();
  const std::vector<FoldGeometry> geometries{{kSquare, kUp}, {kDartAt2, kUp}};
  EXPECT_EQ(unfold_by_flips(triangles, {1, 0}, geometries), 0);
  EXPECT_EQ(triangles, quad());
}

}  // namespace
}  // namespace cmaps
