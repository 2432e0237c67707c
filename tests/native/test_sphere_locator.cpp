// SphereLocator: every direction lands in a triangle whose cone contains it,
// with barycentric coordinates that reproduce it, on exact symmetric cases,
// a real parameterization, slivers, and at the required speed.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/octahedral_grid.h"
#include "consistent_maps/sphere_locator.h"
#include "consistent_maps/spherical_parameterization.h"
#include "test_support.h"

namespace cmaps {
namespace {

std::vector<Vec3> random_directions(size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<Vec3> out;
  while (out.size() < count) {
    const Vec3 d(normal(rng), normal(rng), normal(rng));
    if (d.norm() > 1e-6) out.push_back(d.normalized());
  }
  return out;
}

// The located triangle's cone contains d (up to rounding) and the
// barycentric point of the chordal triangle projects radially onto d.
void expect_valid(const SphereLocator& locator, const Vec3& d, const SphereLocation& at) {
  ASSERT_GE(at.triangle, 0);
  ASSERT_LT(at.triangle, static_cast<int>(locator.triangles().size()));
  double sum = 0;
  for (double w : at.barycentric) {
    EXPECT_GE(w, 0);
    sum += w;
  }
  EXPECT_NEAR(sum, 1, 1e-12);
  const Triangle& t = locator.triangles()[at.triangle];
  const auto& s = locator.sphere();
  const Vec3 p = at.barycentric[0] * s[t[0]] + at.barycentric[1] * s[t[1]] + at.barycentric[2] * s[t[2]];
  EXPECT_LT((p.normalized() - d.normalized()).norm(), 1e-9) << "direction " << d.transpose();
}

SphereLocator octahedron_locator() {
  const TriangleMesh m = test::octahedron();
  return SphereLocator(m.vertices, m.triangles);
}

TEST(SphereLocator, OctahedronVerticesEdgesAndRandomDirections) {
  const SphereLocator locator = octahedron_locator();
  std::vector<Vec3> queries = random_directions(20000, 1);
  const auto& s = locator.sphere();
  for (const Vec3& v : s) queries.push_back(v);
  for (const Triangle& t : locator.triangles())
    for (int c = 0; c < 3; ++c) queries.push_back((s[t[c]] + s[t[(c + 1) % 3]]).normalized());
  queries.push_back(Vec3(1, 1, 1));
  queries.push_back(Vec3(-0.0, 0.0, -2.0));
  for (const Vec3& d : queries) expect_valid(locator, d, locator.locate(d));
}

TEST(SphereLocator, FaceCentreOfOctahedronHasEqualWeights) {
  const SphereLocator locator = octahedron_locator();
  const SphereLocation at = locator.locate(Vec3(3, 3, 3));  // scale does not matter
  EXPECT_EQ(at.triangle, 0);
  for (double w : at.barycentric) EXPECT_NEAR(w, 1.0 / 3, 1e-15);
}

TEST(SphereLocator, RealParameterizationEverywhere) {
  const TriangleMesh mesh = read_mesh(test::shared_mesh("genus0/spot.obj"));
  const SphereResult param = spherical_parameterization(mesh);
  const SphereLocator locator(param.sphere, mesh.triangles);
  std::vector<Vec3> queries = random_directions(200000, 2);
  for (const Vec3& v : param.sphere) queries.push_back(v);
  for (const Triangle& t : mesh.triangles) {
    for (int c = 0; c < 3; ++c) queries.push_back((param.sphere[t[c]] + param.sphere[t[(c + 1) % 3]]).normalized());
    queries.push_back((param.sphere[t[0]] + param.sphere[t[1]] + param.sphere[t[2]]).normalized());
  }
  const std::vector<SphereLocation> found = locator.locate_all(queries, 2);
  for (size_t q = 0; q < queries.size(); ++q) expect_valid(locator, queries[q], found[q]);
  // A vertex's own direction gives it weight one.
  for (size_t v = 0; v < param.sphere.size(); ++v) {
    const SphereLocation& at = found[200000 + v];
    const Triangle& t = mesh.triangles[at.triangle];
    double own = 0;
    for (int c = 0; c < 3; ++c) own += t[c] == static_cast<int>(v) ? at.barycentric[c] : 0;
    EXPECT_NEAR(own, 1, 1e-9) << "vertex " << v;
  }
}

TEST(SphereLocator, DirectionsOnCubeEdgesAndCellBoundaries) {
  // The cube map's own seams: cube edges, corners and every cell boundary line.
  const TriangleMesh mesh = read_mesh(test::shared_mesh("genus0/spot_low.obj"));
  const SphereResult param = spherical_parameterization(mesh);
  const SphereLocator locator(param.sphere, mesh.triangles);
  const int r = locator.cells_per_face_side();
  std::vector<Vec3> queries;
  for (int a = 0; a <= r; ++a) {
    const double u = -1 + 2.0 * a / r;
    for (double v : {-1.0, -0.5, 0.0, 1.0 / 3, 1.0}) {
      for (double s : {1.0, -1.0}) {
        queries.push_back(Vec3(s, u, v));
        queries.push_back(Vec3(u, s, v));
        queries.push_back(Vec3(v, u, s));
      }
    }
  }
  for (const Vec3& d : queries) expect_valid(locator, d, locator.locate(d));
}

TEST(SphereLocator, SliversAroundANearlyCoincidentVertex) {
  // One octahedron face split at a point 1e-9 from its corner: two slivers
  // and a triangle almost equal to the face.
  TriangleMesh m = test::octahedron();
  m.vertices.push_back((m.vertices[0] + 1e-9 * (m.vertices[2] + m.vertices[4])).normalized());
  m.triangles[0] = {0, 2, 6};
  m.triangles.push_back({2, 4, 6});
  m.triangles.push_back({4, 0, 6});
  const SphereLocator locator(m.vertices, m.triangles);
  std::vector<Vec3> queries = {m.vertices[0], m.vertices[6], (m.vertices[0] + m.vertices[6]).normalized()};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> tiny(-2e-9, 2e-9);
  for (int k = 0; k < 2000; ++k) queries.push_back(m.vertices[0] + Vec3(tiny(rng), tiny(rng), tiny(rng)));
  for (const Vec3& d : queries) expect_valid(locator, d, locator.locate(d));
}

TEST(SphereLocator, InterpolatesVectorsMatricesAndStridedValues) {
  const TriangleMesh mesh = read_mesh(test::shared_mesh("genus0/spot_low.obj"));
  const SphereResult param = spherical_parameterization(mesh);
  const SphereLocator locator(param.sphere, mesh.triangles);
  const std::vector<SphereLocation> at = locator.locate_all(random_directions(5000, 4), 2);
  const std::vector<Vec3> positions = locator.interpolate(mesh.vertices, at);
  RowMatrixXd matrix(mesh.vertices.size(), 3);
  std::vector<double> flat;
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    matrix.row(v) = mesh.vertices[v].transpose();
    flat.insert(flat.end(), mesh.vertices[v].data(), mesh.vertices[v].data() + 3);
  }
  const RowMatrixXd from_matrix = locator.interpolate(matrix, at);
  const std::vector<double> from_flat = locator.interpolate(flat, 3, at);
  for (size_t q = 0; q < at.size(); ++q) {
    const Triangle& t = mesh.triangles[at[q].triangle];
    const Vec3 expected = at[q].barycentric[0] * mesh.vertices[t[0]] + at[q].barycentric[1] * mesh.vertices[t[1]] +
                          at[q].barycentric[2] * mesh.vertices[t[2]];
    EXPECT_LT((positions[q] - expected).norm(), 1e-12);
    EXPECT_LT((from_matrix.row(q).transpose() - expected).norm(), 1e-12);
    EXPECT_LT((Vec3(from_flat[3 * q], from_flat[3 * q + 1], from_flat[3 * q + 2]) - expected).norm(), 1e-12);
  }
}

TEST(SphereLocator, RejectsBadInput) {
  TriangleMesh m = test::octahedron();
  EXPECT_THROW(SphereLocator(m.vertices, {}), InvalidInput);
  EXPECT_THROW(SphereLocator(m.vertices, {{{0, 1, 7}}}), InvalidInput);
  std::vector<Vec3> scaled = m.vertices;
  scaled[0] *= 2;
  EXPECT_THROW(SphereLocator(scaled, m.triangles), InvalidInput);
  std::vector<Triangle> flipped = m.triangles;
  std::swap(flipped[3][0], flipped[3][1]);
  EXPECT_THROW(SphereLocator(m.vertices, flipped), InvalidInput);

  const SphereLocator locator(m.vertices, m.triangles);
  EXPECT_THROW(locator.locate(Vec3::Zero()), InvalidInput);
  EXPECT_THROW(locator.locate(Vec3(NAN, 0, 1)), InvalidInput);
  EXPECT_THROW(locator.locate_all({Vec3(1, 0, 0), Vec3::Zero()}), InvalidInput);
  const auto at = locator.locate_all({Vec3(1, 2, 3)});
  EXPECT_THROW(locator.interpolate(std::vector<Vec3>(5), at), InvalidInput);
  EXPECT_THROW(locator.interpolate(std::vector<double>(13), 2, at), InvalidInput);
  EXPECT_THROW(locator.interpolate(std::vector<Vec3>(6), {SphereLocation{8, {1, 0, 0}}}), InvalidInput);
}

TEST(SphereLocator, LocatesMillionsPerSecondOnAHundredThousandFaces) {
  const OctahedralGrid grid = octahedral_grid(224);  // 100,352 faces
  const SphereLocator locator(grid.sphere, grid.triangles);
  const std::vector<Vec3> queries = random_directions(1000000, 5);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<SphereLocation> found = locator.locate_all(queries, 1);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("locate: %.2f M queries/s on one thread\n", queries.size() / seconds / 1e6);
  for (size_t q = 0; q < queries.size(); q += 997) expect_valid(locator, queries[q], found[q]);
  // Lenient against a loaded machine or sanitizers; the benchmark measures properly.
  EXPECT_GT(queries.size() / seconds, 5e5);
}

}  // namespace
}  // namespace cmaps
