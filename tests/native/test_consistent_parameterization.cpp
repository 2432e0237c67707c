// Consistent parameterization of a set: common feature locations, and on sets
// with known correspondence (shared vertex order) the maps agree with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/sphere_locator.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::farthest_points;
using test::diagonal;
using test::shared_mesh;

// Issue 4 aims at 2 %; measured 2.5-2.8 % with 8 features (BENCHMARKS.md).
// A map that ignored the correspondence would be off by 20 % or more.
constexpr double kGroundTruthTolerance = 0.03;
// Cactus 0, 2, 4 with 8 features: 1.6 % and 3.2 % (mean 2.4 %; before the
// maps followed the common map, 2.8 % and 2.5 %); all five poses: mean 3.1 %,
// worst 3.6 % (was 5.5 %, worst 11.3 %; BENCHMARKS.md).
constexpr double kCactusTolerance = 0.035;
// The same with step 7 (align): 1.6 -> 1.6 % and 3.2 -> 1.4 %; all five
// poses: mean 1.6 %, worst 1.99 % (BENCHMARKS.md).
constexpr double kAlignedCactusTolerance = 0.02;


// Mean distance, relative to B's diagonal, between where vertex i of A maps
// on B through the common sphere and vertex i of B.
double ground_truth_error(const ConsistentMember& a, const ConstrainedResult& map_a, const ConsistentMember& b,
                          const ConstrainedResult& map_b) {
  const ParameterizedSurface pb = parameterized_surface(b.mesh, map_b);
  const SphereLocator locator(pb.sphere, pb.surface.triangles);
  const std::vector<Vec3> mapped =
      locator.interpolate(pb.surface.vertices, locator.locate_all(map_a.sphere, 2), 2);
  double sum = 0;
  for (size_t i = 0; i < a.mesh.vertices.size(); ++i) sum += (mapped[i] - b.mesh.vertices[i]).norm();
  return sum / a.mesh.vertices.size() / diagonal(b.mesh);
}

std::vector<ConsistentMember> shared_order_set(const std::vector<std::string>& paths, int features) {
  std::vector<ConsistentMember> members;
  for (const auto& path : paths) members.push_back({read_mesh(shared_mesh(path)), {}});
  const std::vector<int> chosen = farthest_points(members.front().mesh, features);
  for (auto& m : members) m.features = chosen;
  return members;
}

void expect_consistent(const std::vector<ConsistentMember>& members, const ConsistentResult& r) {
  ASSERT_EQ(r.members.size(), members.size());
  for (size_t i = 0; i < members.size(); ++i) {
    const ConstrainedResult& m = r.members[i];
    EXPECT_EQ(m.report.flipped, 0) << i;
    EXPECT_EQ(m.report.degenerate, 0) << i;
    for (size_t k = 0; k < members[i].features.size(); ++k)
      if (members[i].features[k] >= 0)
        EXPECT_LT((m.sphere[members[i].features[k]] - r.feature_locations[k]).norm(), 1e-15);
  }
}

TEST(Consistent, DeformedSpheresMatchTheirKnownCorrespondence) {
  const auto members = shared_order_set({"sets/defsphere/defSphere0.ply", "sets/defsphere/defSphere3.ply",
                                         "sets/defsphere/defSphere6.ply", "sets/defsphere/defSphere9.ply"},
                                        8);
  ConsistentOptions options;
  options.grid = 32;
  const ConsistentResult r = consistent_spherical_parameterization(members, options);
  expect_consistent(members, r);
  for (size_t j = 1; j < members.size(); ++j)
    EXPECT_LT(ground_truth_error(members[0], r.members[0], members[j], r.members[j]), kGroundTruthTolerance) << j;
}

TEST(Consistent, CactusPosesMatchTheirKnownCorrespondence) {
  const auto members =
      shared_order_set({"sets/cactus/cactus0.ply", "sets/cactus/cactus2.ply", "sets/cactus/cactus4.ply"}, 8);
  const ConsistentResult r = consistent_spherical_parameterization(members);
  expect_consistent(members, r);
  for (size_t j = 1; j < members.size(); ++j)
    EXPECT_LT(ground_truth_error(members[0], r.members[0], members[j], r.members[j]), kCactusTolerance) << j;
}

// Step 7 (ConsistentOptions::align) on the same poses: every map but the
// first member's refitted towards it. Features stay exact, no map folds,
// each member keeps 85 % of its own efficiency, and the poses' mean error
// drops below what the six steps alone reach (1.6 / 3.2 -> 1.6 / 1.4 %).
TEST(Consistent, AlignedPosesSlideLessBetweenTheFeatures) {
  const auto members =
      shared_order_set({"sets/cactus/cactus0.ply", "sets/cactus/cactus2.ply", "sets/cactus/cactus4.ply"}, 8);
  const ConsistentResult plain = consistent_spherical_parameterization(members);
  ConsistentOptions options;
  options.align = true;
  const ConsistentResult aligned = consistent_spherical_parameterization(members, options);
  expect_consistent(members, aligned);
  EXPECT_EQ(aligned.members[0].sphere, plain.members[0].sphere);  // the reference stays
  double before = 0, after = 0;
  for (size_t j = 1; j < members.size(); ++j) {
    const double b = ground_truth_error(members[0], plain.members[0], members[j], plain.members[j]);
    const double a = ground_truth_error(members[0], aligned.members[0], members[j], aligned.members[j]);
    std::cout << "cactus pose " << j << ": " << 100 * b << " -> " << 100 * a << " %\n";
    EXPECT_LT(a, kAlignedCactusTolerance) << j;
    before += b, after += a;
    const double own = spherical_parameterization(members[j].mesh).report.efficiency;
    EXPECT_GE(aligned.members[j].report.efficiency, 0.85 * own) << j;
  }
  EXPECT_LT(after, 0.8 * before);
}

// Cactus 0, 2, 4 with 8 features: seeds 3, 4, 5 alone give 8.4 / 3.7, 2.8 / 2.5
// and 8.2 / 4.1 % (one arm's map twisted in 3 and 5); their efficiencies
// over the members' own give 0.98, 1.11, 0.98. Restarts from seed 3 keep 4.
TEST(Consistent, RestartsKeepTheRunThatSuitsEveryMember) {
  const auto members =
      shared_order_set({"sets/cactus/cactus0.ply", "sets/cactus/cactus2.ply", "sets/cactus/cactus4.ply"}, 8);
  ConsistentOptions options;
  options.sphere.seed = 3;
  options.restarts = 3;
  const ConsistentResult r = consistent_spherical_parameterization(members, options);
  expect_consistent(members, r);
  ASSERT_EQ(r.restart_suitability.size(), 3u);
  const auto best = std::max_element(r.restart_suitability.begin(), r.restart_suitability.end());
  EXPECT_EQ(r.restart, best - r.restart_suitability.begin());
  EXPECT_EQ(r.suitability, *best);
  EXPECT_GT(*best, *std::min_element(r.restart_suitability.begin(), r.restart_suitability.end()));
  for (size_t j = 1; j < members.size(); ++j)
    EXPECT_LT(ground_truth_error(members[0], r.members[0], members[j], r.members[j]), kCactusTolerance) << j;
  // The run kept is the single run with its seed.
  options.sphere.seed = 3 + r.restart;
  options.restarts = 1;
  const ConsistentResult single = consistent_spherical_parameterization(members, options);
  for (size_t i = 0; i < members.size(); ++i) EXPECT_EQ(single.members[i].sphere, r.members[i].sphere) << i;
}

TEST(Consistent, MissingFeaturesAndLaterMembers) {
  auto members = shared_order_set({"sets/defsphere/defSphere1.ply", "sets/defsphere/defSphere2.ply",
                                   "sets/defsphere/defSphere4.ply"},
                                  8);
  members[2].features[5] = -1;  // this member lacks one feature
  ConsistentOptions options;
  options.grid = 32;
  const ConsistentResult r = consistent_spherical_parameterization(members, options);
  expect_consistent(members, r);
  ConsistentMember later{read_mesh(shared_mesh("sets/defsphere/defSphere5.ply")), members[0].features};
  later.features[0] = -1;
  const ConstrainedResult added = parameterize_to_locations(later, r.feature_locations);
  EXPECT_EQ(added.report.flipped, 0);
  EXPECT_LT((added.sphere[later.features[1]] - r.feature_locations[1]).norm(), 1e-15);
}

TEST(Consistent, ResultsDoNotDependOnPositionOrScale) {
  auto members = shared_order_set({"sets/defsphere/defSphere0.ply", "sets/defsphere/defSphere7.ply"}, 8);
  ConsistentOptions options;
  options.grid = 32;
  const ConsistentResult a = consistent_spherical_parameterization(members, options);
  for (Vec3& v : members[1].mesh.vertices) v = v * 250 + Vec3(1000, -30, 4);
  const ConsistentResult b = consistent_spherical_parameterization(members, options);
  for (size_t k = 0; k < a.feature_locations.size(); ++k)
    EXPECT_LT((a.feature_locations[k] - b.feature_locations[k]).norm(), 0.02) << k;
}

TEST(Consistent, RemeshesShareConnectivityAndFeatureVertices) {
  const auto members =
      shared_order_set({"sets/defsphere/defSphere0.ply", "sets/defsphere/defSphere8.ply"}, 8);
  ConsistentOptions options;
  options.grid = 32;
  const ConsistentResult r = consistent_spherical_parameterization(members, options);
  const ConsistentRemesh remesh = consistent_remesh(members, r, 16);
  ASSERT_EQ(remesh.positions.size(), 2u);
  EXPECT_EQ(remesh.positions[0].size(), remesh.sphere.size());
  for (size_t k = 0; k < members[0].features.size(); ++k) {
    // Each member's feature vertex lands on its own feature point.
    for (size_t i = 0; i < members.size(); ++i)
      EXPECT_LT((remesh.positions[i][remesh.feature_vertices[k]] - members[i].mesh.vertices[members[i].features[k]])
                    .norm(),
                1e-9 * diagonal(members[i].mesh));
  }
}

TEST(Consistent, BadInputIsRefused) {
  auto members = shared_order_set({"sets/defsphere/defSphere0.ply", "sets/defsphere/defSphere1.ply"}, 4);
  auto refused = [](const std::vector<ConsistentMember>& m, const std::string& text) {
    try {
      consistent_spherical_parameterization(m);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  auto bad = members;
  bad[1].features.pop_back();
  refused(bad, "lists 3 features");
  bad = members;
  bad[1].features[0] = 99999;
  refused(bad, "out of range");
  bad = members;
  bad[0].features[0] = bad[1].features[1] = -1;
  refused(bad, "no mesh has every feature");
  bad = members;
  bad[1].features[0] = bad[1].features[1] = -1;
  refused(bad, "fewer than 3");
  refused({members[0]}, "at least 2");
  bad = members;
  bad[1].mesh = read_mesh(shared_mesh("higher-genus/torus.obj"));
  bad[1].features = {0, 1, 2, 3};
  EXPECT_THROW(consistent_spherical_parameterization(bad), TopologyError);
}

}  // namespace
}  // namespace cmaps
