// SurfaceLocator: the nearest point of a mesh, against a brute force over
// every triangle (projection onto the plane when it falls inside, else the
// nearest of the three edges) on a real mesh, on exact cases of each Voronoi
// region of a triangle, on zero-area triangles, and bad input refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/surface_locator.h"
#include "test_support.h"

namespace cmaps {
namespace {

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

// Distance from p to triangle abc, computed differently from the locator.
double triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  if (n.squaredNorm() > 1e-24) {
    const Vec3 q = p - n.dot(p - a) / n.squaredNorm() * n;  // projection onto the plane
    const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                        (a - c).cross(q - c).dot(n) >= 0;
    if (inside) return (p - q).norm();
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

Vec3 at(const TriangleMesh& mesh, const SurfaceLocation& l) {
  const Triangle& t = mesh.triangles[l.triangle];
  return l.barycentric[0] * mesh.vertices[t[0]] + l.barycentric[1] * mesh.vertices[t[1]] +
         l.barycentric[2] * mesh.vertices[t[2]];
}

void expect_valid(const SurfaceLocation& l) {
  ASSERT_GE(l.triangle, 0);
  double sum = 0;
  for (double w : l.barycentric) {
    EXPECT_GE(w, -1e-12);
    sum += w;
  }
  EXPECT_NEAR(sum, 1, 1e-12);
}

TEST(SurfaceLocator, FindsTheNearestPointOfARealMeshLikeABruteForce) {
  const TriangleMesh mesh = read_mesh(test::shared_mesh("genus0/spot_low.obj"));
  const SurfaceLocator locator(mesh.vertices, mesh.triangles);
  Vec3 low = mesh.vertices[0], high = low;
  for (const Vec3& v : mesh.vertices) low = low.cwiseMin(v), high = high.cwiseMax(v);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-0.2, 1.2);  // inside the box and around it
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i)
    points.push_back(low + Vec3(unit(rng), unit(rng), unit(rng)).cwiseProduct(high - low));
  const std::vector<SurfaceLocation> found = locator.locate_all(points, 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const Triangle& t : mesh.triangles)
      best = std::min(best, triangle_distance(points[i], mesh.vertices[t[0]], mesh.vertices[t[1]],
                                              mesh.vertices[t[2]]));
    expect_valid(found[i]);
    EXPECT_NEAR(found[i].distance, best, 1e-9) << "point " << i;
    EXPECT_NEAR((at(mesh, found[i]) - points[i]).norm(), found[i].distance, 1e-9) << "point " << i;
  }
}

TEST(SurfaceLocator, PointsOnTheSurfaceLocateWhereTheyAre) {
  const TriangleMesh mesh = read_mesh(test::shared_mesh("genus0/spot_low.obj"));
  const SurfaceLocator locator(mesh.vertices, mesh.triangles);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 500; ++i) {
    SurfaceLocation truth;
    truth.triangle = int(rng() % mesh.triangles.size());
    const double u = unit(rng), v = unit(rng) * (1 - u);
    truth.barycentric = {1 - u - v, u, v};
    const SurfaceLocation l = locator.locate(at(mesh, truth));
    expect_valid(l);
    EXPECT_LT(l.distance, 1e-12);
    EXPECT_LT((at(mesh, l) - at(mesh, truth)).norm(), 1e-12);
  }
}

TEST(SurfaceLocator, EveryRegionOfATriangle) {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  mesh.triangles = {{{0, 1, 2}}};
  const SurfaceLocator locator(mesh.vertices, mesh.triangles);
  struct Case {
    Vec3 point;
    std::array<double, 3> barycentric;
    double distance;
  };
  const Case cases[] = {
      {{0.5, 0.5, 3}, {0.5, 0.25, 0.25}, 3},               // above the face
      {{-1, -1, 1}, {1, 0, 0}, std::sqrt(3.0)},            // beyond corner a
      {{3, -1, 0}, {0, 1, 0}, std::sqrt(2.0)},             // beyond corner b
      {{-1, 3, 0}, {0, 0, 1}, std::sqrt(2.0)},             // beyond corner c
      {{1, -2, 0}, {0.5, 0.5, 0}, 2},                      // beyond edge ab
      {{-2, 1, 0}, {0.5, 0, 0.5}, 2},                      // beyond edge ca
      {{2, 2, 0}, {0, 0.5, 0.5}, std::sqrt(2.0)},          // beyond edge bc
  };
  for (const Case& c : cases) {
    const SurfaceLocation l = locator.locate(c.point);
    EXPECT_EQ(l.triangle, 0);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(l.barycentric[k], c.barycentric[k], 1e-12) << c.point.transpose();
    EXPECT_NEAR(l.distance, c.distance, 1e-12) << c.point.transpose();
  }
}

TEST(SurfaceLocator, ZeroAreaTrianglesAreSearchedAlongTheirEdges) {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {5, 5, 5}};
  mesh.triangles = {{{0, 1, 2}}, {{3, 3, 3}}};  // collinear corners; one point
  const SurfaceLocator locator(mesh.vertices, mesh.triangles);
  SurfaceLocation l = locator.locate({2, 1, 0});
  EXPECT_EQ(l.triangle, 0);
  EXPECT_NEAR(l.distance, 1, 1e-12);
  EXPECT_NEAR((at(mesh, l) - Vec3(2, 0, 0)).norm(), 0, 1e-12);
  l = locator.locate({5, 5, 6});
  EXPECT_EQ(l.triangle, 1);
  EXPECT_NEAR(l.distance, 1, 1e-12);
}

TEST(SurfaceLocator, BadInputIsRefused) {
  const TriangleMesh tetra = test::tetrahedron();
  EXPECT_THROW(SurfaceLocator(tetra.vertices, {}), InvalidInput);
  EXPECT_THROW(SurfaceLocator(tetra.vertices, {{{0, 1, 4}}}), InvalidInput);
  std::vector<Vec3> bad = tetra.vertices;
  bad[2].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SurfaceLocator(bad, tetra.triangles), InvalidInput);
  const SurfaceLocator locator(tetra.vertices, tetra.triangles);
  EXPECT_THROW(locator.locate(Vec3(0, std::numeric_limits<double>::infinity(), 0)), InvalidInput);
  EXPECT_THROW(locator.locate_all({Vec3(0, 0, 0), Vec3(std::nan(""), 0, 0)}), InvalidInput);
}

}  // namespace
}  // namespace cmaps
