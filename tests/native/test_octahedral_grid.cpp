// The flat-octahedron grid: a closed, consistently oriented genus-0 sphere
// triangulation whose image boundary is glued by the octahedral symmetry.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "consistent_maps/errors.h"
#include "consistent_maps/octahedral_grid.h"
#include "consistent_maps/stretch_metric.h"

namespace cmaps {
namespace {

class OctahedralGridTest : public ::testing::TestWithParam<int> {};

TEST_P(OctahedralGridTest, ClosedOrientedGenusZeroTriangulationOfTheSphere) {
  const int n = GetParam();
  const OctahedralGrid g = octahedral_grid(n);
  EXPECT_EQ(g.n, n);
  ASSERT_EQ(g.sphere.size(), static_cast<size_t>(n * n + 2));
  ASSERT_EQ(g.triangles.size(), static_cast<size_t>(2 * n * n));
  // Every directed edge appears once and its reverse once: closed, manifold, oriented.
  std::map<std::pair<int, int>, int> directed;
  double area = 0;
  for (const Triangle& t : g.triangles) {
    for (int c = 0; c < 3; ++c) ++directed[{t[c], t[(c + 1) % 3]}];
    const Vec3 &a = g.sphere[t[0]], &b = g.sphere[t[1]], &c = g.sphere[t[2]];
    EXPECT_GT(a.dot(b.cross(c)), 0);
    area += signed_spherical_area(a, b, c);
    // Each triangle lies on one octahedron face: no coordinate changes sign.
    for (int k = 0; k < 3; ++k) EXPECT_GE(std::min({a[k] * b[k], b[k] * c[k], c[k] * a[k]}), -1e-15);
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  const long edges = static_cast<long>(directed.size()) / 2;
  EXPECT_EQ(static_cast<long>(g.sphere.size()) - edges + static_cast<long>(g.triangles.size()), 2);
  EXPECT_NEAR(area, 4 * M_PI, 1e-9);
  for (const Vec3& v : g.sphere) EXPECT_NEAR(v.norm(), 1, 1e-15);
}

TEST_P(OctahedralGridTest, BoundaryPixelsAreMirroredAcrossEdgeMidpoints) {
  const int n = GetParam(), h = n / 2;
  const OctahedralGrid g = octahedral_grid(n);
  ASSERT_EQ(g.pixel_vertex.size(), static_cast<size_t>((n + 1) * (n + 1)));
  for (int k = 0; k <= n; ++k) {
    EXPECT_EQ(g.vertex(0, k), g.vertex(0, n - k));
    EXPECT_EQ(g.vertex(n, k), g.vertex(n, n - k));
    EXPECT_EQ(g.vertex(k, 0), g.vertex(n - k, 0));
    EXPECT_EQ(g.vertex(k, n), g.vertex(n - k, n));
  }
  EXPECT_EQ(g.vertex(0, 0), g.vertex(n, n));
  EXPECT_EQ(g.vertex(0, n), g.vertex(n, 0));
  EXPECT_EQ(g.vertex(0, 0), g.vertex(0, n));
  EXPECT_LT((g.sphere[g.vertex(0, 0)] - Vec3(0, 0, -1)).norm(), 1e-15);
  EXPECT_LT((g.sphere[g.vertex(h, h)] - Vec3(0, 0, 1)).norm(), 1e-15);
  // The diamond's corners are the equator's axis points, and interior pixels are unique.
  EXPECT_LT((g.sphere[g.vertex(h, n)] - Vec3(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((g.sphere[g.vertex(n, h)] - Vec3(0, 1, 0)).norm(), 1e-15);
  std::set<int> interior;
  for (int i = 1; i < n; ++i)
    for (int j = 1; j < n; ++j) interior.insert(g.vertex(i, j));
  EXPECT_EQ(interior.size(), static_cast<size_t>((n - 1) * (n - 1)));
}

INSTANTIATE_TEST_SUITE_P(Sizes, OctahedralGridTest, ::testing::Values(2, 4, 6, 16, 64));

TEST(OctahedralGrid, SmallestIsTheOctahedron) {
  const OctahedralGrid g = octahedral_grid(2);
  for (const Vec3& v : g.sphere) EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 1, 0);
}

TEST(OctahedralGrid, RejectsOddOrTooSmallSizes) {
  for (int n : {-2, 0, 1, 3, 17}) EXPECT_THROW(octahedral_grid(n), InvalidInput) << n;
}

}  // namespace
}  // namespace cmaps
