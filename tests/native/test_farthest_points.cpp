// Farthest-point sampling (intersurface/farthest_points.h): along the edges
// it reaches the tip of the other of two arms lying side by side, which a
// straight line finds close; vertices no triangle uses are never picked.
#include <gtest/gtest.h>

#include "intersurface/farthest_points.h"

namespace cmaps {
namespace {

// A flat U: the unit square as a 20 x 20 grid with a slot x in (0.45, 0.55),
// y > 0.1 cut out (its vertices stay, unused), so the arms' tops are 0.1
// apart in space and about 1.9 apart along the edges.
TriangleMesh flat_u() {
  TriangleMesh m;
  constexpr int n = 20;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back({double(i) / n, double(j) / n, 0});
  const auto at = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i == 9 || i == 10) && j >= 2) continue;  // the slot
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

TEST(Spread, AlongTheEdgesReachesTheOtherArmsTip) {
  const TriangleMesh u = flat_u();
  const std::vector<int> seeds{20 * 21 + 9};  // the left arm's inner top corner (0.45, 1)
  Spread along(u, /*along_edges=*/true), straight(u, /*along_edges=*/false);
  const Vec3 far_along = u.vertices[along.next(seeds)], far_straight = u.vertices[straight.next(seeds)];
  EXPECT_EQ(far_along.y(), 1);  // the top of the right arm
  EXPECT_GE(far_along.x(), 0.55);
  EXPECT_EQ(far_straight, Vec3(1, 0, 0));  // the far corner below
}

TEST(Spread, NeverPicksAnUnusedVertexAlongTheEdges) {
  const TriangleMesh u = flat_u();
  std::vector<int> seeds{0};
  Spread along(u, /*along_edges=*/true);
  for (int k = 0; k < 30; ++k) {
    const int v = along.next(seeds);
    ASSERT_GE(v, 0);
    const Vec3& p = u.vertices[v];
    EXPECT_FALSE(p.x() > 0.45 + 1e-9 && p.x() < 0.55 - 1e-9 && p.y() > 0.1 + 1e-9) << "vertex " << v;
    seeds.push_back(v);
  }
}

TEST(Spread, StartsFromTheVertexFarthestFromTheCentroid) {
  TriangleMesh m = flat_u();
  m.vertices[0] = {-1, -1, 0};
  EXPECT_EQ(farthest_from_centroid(m), 0);
  EXPECT_EQ(spread_vertex(m, 0), 0);
  EXPECT_EQ(m.vertices[spread_vertex(m, 1)], Vec3(1, 1, 0));
}

}  // namespace
}  // namespace cmaps
