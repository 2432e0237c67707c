// Constrained spherical parameterization: features exactly on their targets,
// bijective, low stretch; robust to random, adjacent and badly placed features.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::farthest_points;
using test::shared_mesh;

// Well-spread features: farthest-point sampling by Euclidean distance.

std::vector<int> random_features(const TriangleMesh& mesh, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(mesh.vertices.size()) - 1);
  std::set<int> chosen;
  while (static_cast<int>(chosen.size()) < count) chosen.insert(pick(rng));
  return {chosen.begin(), chosen.end()};
}

void expect_valid(const TriangleMesh& mesh, const std::vector<int>& features, const ConstrainedResult& r) {
  EXPECT_EQ(r.report.flipped, 0);
  EXPECT_EQ(r.report.degenerate, 0);
  EXPECT_NEAR(r.report.spherical_area_sum, 4 * M_PI, 1e-6);
  EXPECT_EQ(r.max_constraint_error, 0.0);
  ASSERT_EQ(r.sphere.size(), mesh.vertices.size());
  for (size_t i = 0; i < features.size(); ++i) EXPECT_EQ(r.sphere[features[i]], r.targets[i]);
  for (const Vec3& p : r.sphere) EXPECT_NEAR(p.norm(), 1.0, 1e-12);
  // The refined triangulation covers the input vertices and the Steiner vertices.
  int largest = 0;
  for (const Triangle& t : r.triangles) largest = std::max({largest, t[0], t[1], t[2]});
  EXPECT_EQ(largest + 1, static_cast<int>(mesh.vertices.size() + r.steiner.size()));
  for (const SteinerVertex& s : r.steiner) {
    EXPECT_NEAR(s.weights[0] + s.weights[1] + s.weights[2], 1.0, 1e-12);
    EXPECT_NEAR(s.sphere.norm(), 1.0, 1e-12);
  }
  // Every refined triangle lies in its input triangle: its corners are input
  // corners or Steiner vertices made of that triangle's corners only.
  ASSERT_EQ(r.input_triangle.size(), r.triangles.size());
  const int n = static_cast<int>(mesh.vertices.size());
  for (size_t f = 0; f < r.triangles.size(); ++f) {
    const Triangle& parent = mesh.triangles[r.input_triangle[f]];
    auto in_parent = [&](int v) { return std::find(parent.begin(), parent.end(), v) != parent.end(); };
    for (int v : r.triangles[f]) {
      if (v < n) {
        EXPECT_TRUE(in_parent(v)) << f;
      } else {
        for (int k = 0; k < 3; ++k)
          if (r.steiner[v - n].weights[k] > 0) EXPECT_TRUE(in_parent(r.steiner[v - n].vertices[k])) << f;
      }
    }
  }
}

struct WellSpread {
  const char* path;
  int features;
};

class ConstrainedWellSpread : public ::testing::TestWithParam<WellSpread> {};

// With targets from the unconstrained map, constraints cost little stretch.
TEST_P(ConstrainedWellSpread, KeepsMostOfTheUnconstrainedEfficiency) {
  const TriangleMesh mesh = read_mesh(shared_mesh(GetParam().path));
  const std::vector<int> features = farthest_points(mesh, GetParam().features);
  const SphereResult free = spherical_parameterization(mesh);
  std::vector<Vec3> targets;
  for (int v : features) targets.push_back(free.sphere[v]);
  const ConstrainedResult r = constrained_spherical_parameterization(mesh, features, targets);
  expect_valid(mesh, features, r);
  EXPECT_GE(r.report.efficiency, 0.9 * free.report.efficiency);
  EXPECT_LE(r.steiner.size(), 0.05 * mesh.vertices.size());
}

INSTANTIATE_TEST_SUITE_P(Meshes, ConstrainedWellSpread,
                         ::testing::Values(WellSpread{"genus0/bunny.off", 8}, WellSpread{"genus0/bunny.off", 20},
                                           WellSpread{"genus0/bunny.off", 40}, WellSpread{"heads/maxplanck.off", 8},
                                           WellSpread{"heads/maxplanck.off", 20},
                                           WellSpread{"heads/maxplanck.off", 40},
                                           // Features at the tips of thin extremities: hooves, fingers.
                                           WellSpread{"large/horse.ply", 20}, WellSpread{"large/armadillo.obj", 40}),
                         [](const auto& info) {
                           std::string name = info.param.path;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name + "_" + std::to_string(info.param.features);
                         });

class ConstrainedRandom : public ::testing::TestWithParam<const char*> {};

// Seeded random features with automatic targets: always a valid map.
TEST_P(ConstrainedRandom, FourToThirtyTwoFeatures) {
  const TriangleMesh mesh = read_mesh(shared_mesh(GetParam()));
  for (int count : {4, 8, 16, 32}) {
    SCOPED_TRACE(count);
    const std::vector<int> features = random_features(mesh, count, 1000 + count);
    expect_valid(mesh, features, constrained_spherical_parameterization(mesh, features, {}));
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, ConstrainedRandom,
                         ::testing::Values("genus0/bumpy.off", "genus0/bunny.off", "genus0/camel.off",
                                           "genus0/cat-low-resolution.obj", "genus0/cheburashka.off",
                                           "genus0/cow.off", "genus0/decimated-knight.off", "genus0/hand_closed.obj",
                                           "genus0/koala_low_resolution.obj", "genus0/penguin.obj", "genus0/pig.off",
                                           "genus0/sphere.obj", "genus0/spot.obj", "genus0/spot_low.obj",
                                           "genus0/venus_small.off", "heads/egea.off", "heads/goathead.obj",
                                           "heads/mannequin.off", "heads/max_small.obj", "heads/maxplanck.off",
                                           "heads/moaimoai.off", "heads/nefertiti.obj", "large/armadillo.obj",
                                           "large/bunny_hr.obj", "large/dinosaur.off", "large/gargoyle.off",
                                           "large/handman.off", "large/horse.ply", "large/venus.off",
                                           "sets/defsphere/defSphere3.ply", "sets/cactus/cactus2.ply"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(Constrained, PermutedTargetsStillGiveABijection) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/spot_low.obj"));
  const std::vector<int> features = farthest_points(mesh, 8);
  const SphereResult free = spherical_parameterization(mesh);
  std::vector<Vec3> targets;
  for (int v : features) targets.push_back(free.sphere[v]);
  std::mt19937 rng(5);
  std::shuffle(targets.begin(), targets.end(), rng);
  expect_valid(mesh, features, constrained_spherical_parameterization(mesh, features, targets));
}

TEST(Constrained, AdjacentFeatures) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/cow.off"));
  const Triangle& t = mesh.triangles[100];
  std::vector<int> features{t[0], t[1], t[2]};
  for (int v : farthest_points(mesh, 6))
    if (std::find(features.begin(), features.end(), v) == features.end()) features.push_back(v);
  expect_valid(mesh, features, constrained_spherical_parameterization(mesh, features, {}));
}

TEST(Constrained, ThreeFeaturesNeedFreeBaseVertices) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/pig.off"));
  const std::vector<int> features = farthest_points(mesh, 3);
  const std::vector<Vec3> targets{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const ConstrainedResult r = constrained_spherical_parameterization(mesh, features, targets);
  expect_valid(mesh, features, r);
  EXPECT_GE(r.auxiliary_vertices, 1);
}

TEST(Constrained, TargetsAreNormalized) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/spot_low.obj"));
  const std::vector<int> features = farthest_points(mesh, 4);
  const std::vector<Vec3> targets{{2, 0, 0}, {0, 3, 0}, {0, 0, 0.5}, {-1, -1, -1}};
  const ConstrainedResult r = constrained_spherical_parameterization(mesh, features, targets);
  expect_valid(mesh, features, r);
  EXPECT_EQ(r.targets[1], Vec3(0, 1, 0));
}

TEST(Constrained, BadInputIsRefused) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/spot_low.obj"));
  const std::vector<Vec3> three{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  auto refused = [&](const std::vector<int>& features, const std::vector<Vec3>& targets, const std::string& text) {
    try {
      constrained_spherical_parameterization(mesh, features, targets);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  refused({1, 2}, {}, "at least 3 features");
  refused({1, 2, 2}, {}, "given twice");
  refused({1, 2, 100000}, {}, "out of range");
  refused({1, 2, -1}, {}, "out of range");
  refused({1, 2, 3}, {{1, 0, 0}, {1, 0, 0}, {0, 0, 1}}, "are equal");
  refused({1, 2, 3}, {{1, 0, 0}, {0, NAN, 0}, {0, 0, 1}}, "not finite");
  refused({1, 2, 3}, {{1, 0, 0}, {0, 0, 0}, {0, 0, 1}}, "zero vector");
  refused({1, 2, 3}, {{1, 0, 0}, {0, 1, 0}}, "2 targets for 3 features");
  EXPECT_THROW(constrained_spherical_parameterization(read_mesh(shared_mesh("higher-genus/torus.obj")), {1, 2, 3},
                                                      three),
               TopologyError);
}

}  // namespace
}  // namespace cmaps
