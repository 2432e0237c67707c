// Resampling through a spherical parameterization reproduces the surface,
// and features snap to distinct grid samples.
#include <gtest/gtest.h>

#include <cmath>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/octahedral_grid.h"
#include "consistent_maps/remesh.h"
#include "consistent_maps/sphere_locator.h"
#include "consistent_maps/spherical_parameterization.h"
#include "test_support.h"

namespace cmaps {
namespace {

// Distance from p to triangle (a, b, c), by projection and edge clamping.
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 q = p - n * (p - a).dot(n) / n.squaredNorm();
  const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                      (a - c).cross(q - c).dot(n) >= 0;
  if (inside) return (p - q).norm();
  auto segment = [&](const Vec3& s, const Vec3& e) {
    const double t = std::clamp((p - s).dot(e - s) / (e - s).squaredNorm(), 0.0, 1.0);
    return (p - (s + t * (e - s))).norm();
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

TEST(Resample, RadiallyParameterizedEllipsoidGivesTheEllipsoid) {
  const Vec3 radii(2, 1, 0.5);
  const OctahedralGrid fine = octahedral_grid(128);
  TriangleMesh ellipsoid{{}, fine.triangles};
  for (const Vec3& d : fine.sphere) ellipsoid.vertices.push_back(d / d.cwiseQuotient(radii).norm());
  // The mesh's own directions give back its vertices exactly.
  const std::vector<Vec3> same = resample(ellipsoid, fine.sphere, fine.sphere);
  for (size_t v = 0; v < same.size(); ++v) EXPECT_LT((same[v] - ellipsoid.vertices[v]).norm(), 1e-12);
  // Any other samples land within the chordal error of the analytic surface.
  const OctahedralGrid coarse = octahedral_grid(50);
  const std::vector<Vec3> remesh = resample(ellipsoid, fine.sphere, coarse.sphere);
  double worst = 0;
  for (const Vec3& p : remesh) worst = std::max(worst, std::abs(p.cwiseQuotient(radii).norm() - 1));
  EXPECT_LT(worst, 2e-3);
}

TEST(Resample, RealMeshRemeshLiesOnTheInputSurface) {
  const TriangleMesh spot = read_mesh(test::shared_mesh("genus0/spot.obj"));
  const SphereResult param = spherical_parameterization(spot);
  const OctahedralGrid grid = octahedral_grid(64);
  const std::vector<Vec3> remesh = resample(spot, param.sphere, grid.sphere);
  ASSERT_EQ(remesh.size(), grid.sphere.size());
  const SphereLocator locator(param.sphere, spot.triangles);
  const std::vector<SphereLocation> at = locator.locate_all(grid.sphere);
  Vec3 lo = spot.vertices[0], hi = lo;
  for (const Vec3& v : spot.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double diagonal = (hi - lo).norm();
  for (size_t v = 0; v < remesh.size(); ++v) {
    const Triangle& t = spot.triangles[at[v].triangle];
    EXPECT_LT(point_triangle_distance(remesh[v], spot.vertices[t[0]], spot.vertices[t[1]], spot.vertices[t[2]]),
              1e-12 * diagonal);
  }
  // A bijective map covers the whole surface: the remesh's area is close to the input's.
  auto area = [](const std::vector<Vec3>& x, const std::vector<Triangle>& triangles) {
    double sum = 0;
    for (const Triangle& t : triangles) sum += 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
    return sum;
  };
  EXPECT_NEAR(area(remesh, grid.triangles) / area(spot.vertices, spot.triangles), 1, 0.05);
}

TEST(Resample, RejectsMismatchedParameterization) {
  const TriangleMesh m = test::octahedron();
  EXPECT_THROW(resample(m, {m.vertices.begin(), m.vertices.end() - 1}, {Vec3(1, 0, 0)}), InvalidInput);
  EXPECT_THROW(resample(m, m.vertices, {Vec3::Zero()}), InvalidInput);
}

TEST(SnapFeatures, MovesTheNearestDistinctSamplesExactlyOntoTheFeatures) {
  OctahedralGrid grid = octahedral_grid(32);
  const std::vector<Vec3> original = grid.sphere;
  const std::vector<Vec3> features = {Vec3(1, 2, 3), Vec3(-1, 0.1, 0), Vec3(0.3, -1, -0.2), Vec3(0, 0, 1)};
  const std::vector<int> snapped = snap_features(grid.sphere, features);
  ASSERT_EQ(snapped.size(), features.size());
  for (size_t f = 0; f < features.size(); ++f) {
    const Vec3 unit = features[f].normalized();
    EXPECT_EQ(grid.sphere[snapped[f]], unit);
    for (const Vec3& s : original) EXPECT_GE(original[snapped[f]].dot(unit), s.dot(unit));
  }
  int moved = 0;
  for (size_t s = 0; s < original.size(); ++s) moved += grid.sphere[s] != original[s];
  EXPECT_LE(moved, 4);  // (0, 0, 1) is already a sample
}

TEST(SnapFeatures, RejectsFeaturesSharingASampleAndZeroDirections) {
  OctahedralGrid grid = octahedral_grid(8);
  EXPECT_THROW(snap_features(grid.sphere, {Vec3(1, 0.01, 0), Vec3(1, 0, 0.01)}), InvalidInput);
  EXPECT_THROW(snap_features(grid.sphere, {Vec3::Zero()}), InvalidInput);
  EXPECT_THROW(snap_features(grid.sphere, {Vec3(NAN, 0, 1)}), InvalidInput);
  const std::vector<Vec3> before = octahedral_grid(8).sphere;
  EXPECT_EQ(grid.sphere, before);  // nothing moved after a failure
}

}  // namespace
}  // namespace cmaps
