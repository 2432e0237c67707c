// The stretch metric on cases with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "consistent_maps/stretch_metric.h"

namespace cmaps {
namespace {

// Icosahedron subdivided `level` times, vertices on the unit sphere.
TriangleMesh icosphere(int level) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriangleMesh m;
  for (const Vec3& v : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t),
                        Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1),
                        Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    m.vertices.push_back(v.normalized());
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoint.emplace(key, static_cast<int>(m.vertices.size()));
      if (inserted) m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return it->second;
    };
    std::vector<Triangle> finer;
    for (const Triangle& f : m.triangles) {
      const int a = mid(f[0], f[1]), b = mid(f[1], f[2]), c = mid(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    m.triangles = finer;
  }
  return m;
}

TEST(TriangleStretch, IsometryAndScaling) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.3, 0.8, 0);
  TriangleStretch s = triangle_stretch(a, b, c, a, b, c);
  EXPECT_NEAR(s.l2, 1.0, 1e-12);
  EXPECT_NEAR(s.linf, 1.0, 1e-12);
  s = triangle_stretch(a, b, c, 2 * a, 2 * b, 2 * c);
  EXPECT_NEAR(s.l2, 2.0, 1e-12);
  // The domain may sit in any plane: rotate it out of z = 0.
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  s = triangle_stretch(r * a, r * b, r * c, a, b, c);
  EXPECT_NEAR(s.l2, 1.0, 1e-12);
}

TEST(TriangleStretch, Anisotropic) {
  // x scaled by 3, y kept: singular values 3 and 1.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.2, 1, 0);
  const Eigen::Vector3d scale(3, 1, 1);
  const TriangleStretch s =
      triangle_stretch(a, b, c, a.cwiseProduct(scale), b.cwiseProduct(scale), c.cwiseProduct(scale));
  EXPECT_NEAR(s.l2, std::sqrt((9.0 + 1.0) / 2), 1e-12);
  EXPECT_NEAR(s.linf, 3.0, 1e-12);
}

TEST(TriangleStretch, DegenerateDomainIsInfinite) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0), d(0, 1, 0);
  EXPECT_TRUE(std::isinf(triangle_stretch(a, b, c, a, b, d).l2));
}

TEST(SphericalMap, FineSphereMappedRadiallyIsNearlyIsometric) {
  const TriangleMesh sphere = icosphere(4);
  const SphericalMapReport r = measure_spherical_map(sphere, sphere.vertices);
  EXPECT_TRUE(r.bijective());
  EXPECT_EQ(r.flipped, 0);
  EXPECT_NEAR(r.spherical_area_sum, 4 * M_PI, 1e-9);
  EXPECT_GT(r.efficiency, 0.99);
  EXPECT_LE(r.efficiency, 1.0 + 1e-9);
}

TEST(SphericalMap, EfficiencyIsScaleInvariant) {
  TriangleMesh big = icosphere(3);
  const std::vector<Vec3> sphere = big.vertices;
  for (Vec3& v : big.vertices) v *= 25;
  EXPECT_NEAR(measure_spherical_map(big, sphere).efficiency, measure_spherical_map(icosphere(3), sphere).efficiency,
              1e-12);
}

// Ellipsoid with semi-axes D = diag(a, b, c), parameterized by x -> D x.
// At x, the map's tangent singular values satisfy s1^2 + s2^2 = tr(D^2) - |D x|^2
// and the area element is det(D) |D^-1 x|; integrate on a Fibonacci sphere.
double ellipsoid_efficiency(const Vec3& axes) {
  const int n = 200000;
  double area = 0, stretch = 0;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
    const Vec3 x(r * std::cos(phi), r * std::sin(phi), z);
    const double da = axes.prod() * x.cwiseQuotient(axes).norm();
    area += da;
    stretch += da * 0.5 * (axes.squaredNorm() - x.cwiseProduct(axes).squaredNorm());
  }
  const double l2_squared = stretch / area;
  const double surface_area = area * 4 * M_PI / n;
  return surface_area / (4 * M_PI) / l2_squared;
}

TEST(SphericalMap, EllipsoidMatchesAnalyticIntegral) {
  const Vec3 axes(1.0, 2.0, 3.5);
  TriangleMesh ellipsoid = icosphere(5);
  const std::vector<Vec3> sphere = ellipsoid.vertices;
  for (Vec3& v : ellipsoid.vertices) v = v.cwiseProduct(axes);
  const SphericalMapReport r = measure_spherical_map(ellipsoid, sphere);
  const double expected = ellipsoid_efficiency(axes);
  EXPECT_LT(expected, 0.9);  // far from an isometry, so the comparison means something
  EXPECT_NEAR(r.efficiency, expected, 0.01 * expected);
  EXPECT_TRUE(r.bijective());
}

TEST(SphericalMap, FoldedMapIsCaught) {
  const TriangleMesh mesh = icosphere(2);
  std::vector<Vec3> sphere = mesh.vertices;
  // Push one vertex through its ring: its triangles flip.
  const Triangle& t = mesh.triangles[0];
  sphere[t[0]] = (sphere[t[1]] + sphere[t[2]] - 0.5 * sphere[t[0]]).normalized();
  const SphericalMapReport r = measure_spherical_map(mesh, sphere);
  EXPECT_GT(r.flipped, 0);
  EXPECT_FALSE(r.bijective());
}

TEST(SphericalMap, MirroredMapIsAllFlipped) {
  const TriangleMesh mesh = icosphere(1);
  std::vector<Vec3> sphere = mesh.vertices;
  for (Vec3& v : sphere) v.x() = -v.x();
  const SphericalMapReport r = measure_spherical_map(mesh, sphere);
  EXPECT_EQ(r.flipped, static_cast<int>(mesh.triangles.size()));
  EXPECT_NEAR(r.spherical_area_sum, -4 * M_PI, 1e-9);
}

TEST(SphericalMap, CollapsedMapIsDegenerate) {
  const TriangleMesh mesh = icosphere(1);
  const std::vector<Vec3> sphere(mesh.vertices.size(), Vec3(0, 0, 1));
  const SphericalMapReport r = measure_spherical_map(mesh, sphere);
  EXPECT_EQ(r.degenerate, static_cast<int>(mesh.triangles.size()));
  EXPECT_FALSE(r.bijective());
  EXPECT_TRUE(std::isfinite(r.efficiency));
}

TEST(SphericalArea, OctantIsHalfPi) {
  EXPECT_NEAR(signed_spherical_area(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)), M_PI / 2, 1e-12);
  EXPECT_NEAR(signed_spherical_area(Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0)), -M_PI / 2, 1e-12);
}

}  // namespace
}  // namespace cmaps
