// The k-d tree of common/nearest_point.h against a scan of every point, ties
// included (a grid's points and repeated points are equally near many queries).
#include <gtest/gtest.h>

#include <random>

#include "common/nearest_point.h"

namespace cmaps {
namespace {

// The lowest index among the nearest points, by looking at all of them.
int scanned(const std::vector<Vec3>& points, const Vec3& p) {
  int best = 0;
  for (int i = 1; i < int(points.size()); ++i)
    if ((points[i] - p).squaredNorm() < (points[best] - p).squaredNorm()) best = i;
  return best;
}

TEST(NearestPoint, MatchesAScanOnScatteredPoints) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> along(-1, 1);
  std::vector<Vec3> points(2000);
  for (Vec3& p : points) p = {along(random), 0.2 * along(random), 3 * along(random)};
  const NearestPoint nearest(points);
  for (int q = 0; q < 2000; ++q) {
    const Vec3 p(1.2 * along(random), 0.5 * along(random), 3.5 * along(random));
    ASSERT_EQ(nearest(p), scanned(points, p)) << "query " << q;
  }
}

TEST(NearestPoint, TiesGoToTheLowestIndex) {
  std::vector<Vec3> points;
  for (int copy = 0; copy < 3; ++copy)  // each grid point three times
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j)
        for (int k = 0; k < 10; ++k) points.push_back({double(i), double(j), double(k)});
  const NearestPoint nearest(points);
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const Vec3 on(i, j, 4), between(i + 0.5, j + 0.5, 4.5);  // one nearest point; eight, all as near
      EXPECT_EQ(nearest(on), scanned(points, on));
      EXPECT_EQ(nearest(on), 100 * i + 10 * j + 4);
      EXPECT_EQ(nearest(between), scanned(points, between)) << i << " " << j;
    }
}

TEST(NearestPoint, FewPointsAndNone) {
  EXPECT_EQ(NearestPoint({})(Vec3(1, 2, 3)), 0);
  const std::vector<Vec3> two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(NearestPoint(two)(Vec3(0.9, 5, 0)), 1);
}

}  // namespace
}  // namespace cmaps
