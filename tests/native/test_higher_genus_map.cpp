// Inter-surface maps of genus >= 1 (issue 5): the consistent partition has
// identical connectivity on both meshes, every patch is a disk embedded
// bijectively onto the canonical triangle, and the map through it is valid,
// exact at the features and inverts its reverse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "consistent_maps/errors.h"
#include "consistent_maps/intersurface_map.h"
#include "consistent_maps/mesh_io.h"
#include "intersurface/consistent_partition.h"
#include "intersurface/patch_balance.h"
#include "intersurface/patch_parameterization.h"
#include "intersurface_expectations.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::corner_offsets;
using test::diagonal;
using test::expect_exact_features;
using test::expect_same_images;
using test::expect_valid_points;
using test::farthest_points;
using test::nudged_corner;
using test::shared_mesh;
using test::stretched_copy;

struct Pair {
  const char* a;
  const char* b;
  int genus;
};

// Measured 2-19 % on these pairs: the interpolation over one target triangle
// spreads far where the map stretches most (these pairs are far from
// isometric and their partitions far from matching); a map that does not
// invert its reverse is off by about half the diagonal.
constexpr double kRoundTrip = 0.3;

const Pair kPairs[] = {{"higher-genus/torus.obj", "higher-genus/knot.obj", 1},
                       {"higher-genus/eight.off", "higher-genus/skull.obj", 2}};

// Euler characteristic of a set of triangles (of one mesh).
int euler(const std::vector<Triangle>& triangles, const std::vector<int>& faces) {
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (int f : faces)
    for (int k = 0; k < 3; ++k) {
      const int u = triangles[f][k], w = triangles[f][(k + 1) % 3];
      vertices.insert(u);
      edges.insert(std::minmax(u, w));
    }
  return int(vertices.size()) - int(edges.size()) + int(faces.size());
}

// One base triangulation on both sides, paths meeting only at their ends,
// every patch a disk that embeds bijectively onto its canonical triangle.
void expect_consistent_partition(ConsistentPartition& p, int genus) {
  ASSERT_EQ(p.sides.size(), 2u);
  // One base triangulation, a closed surface of the input's genus: every
  // base edge bounds two base triangles, V - E + F = 2 - 2g.
  const int v = int(p.sides[0].feature_vertex.size()), e = int(p.edges.size()), f = int(p.triangles.size());
  EXPECT_EQ(v - e + f, 2 - 2 * genus);
  std::vector<int> uses(e, 0);
  for (const BaseTriangle& t : p.triangles) {
    EXPECT_EQ(std::set<int>(t.corners.begin(), t.corners.end()).size(), 3u);
    for (int k = 0; k < 3; ++k) {
      ++uses[t.edges[k]];
      const auto& ends = p.edges[t.edges[k]];
      EXPECT_EQ(ends[t.reversed[k] ? 1 : 0], t.corners[k]);
      EXPECT_EQ(ends[t.reversed[k] ? 0 : 1], t.corners[(k + 1) % 3]);
    }
  }
  for (int n : uses) EXPECT_EQ(n, 2);

  for (PartitionSide& side : p.sides) {
    // Each path joins its base edge's features and the paths meet only there.
    std::map<int, int> owner;
    for (int i = 0; i < e; ++i) {
      const auto& path = side.paths[i];
      EXPECT_EQ(path.front(), side.feature_vertex[p.edges[i][0]]);
      EXPECT_EQ(path.back(), side.feature_vertex[p.edges[i][1]]);
      for (std::size_t k = 1; k + 1 < path.size(); ++k) EXPECT_TRUE(owner.emplace(path[k], i).second);
    }
    for (int fv : side.feature_vertex) EXPECT_FALSE(owner.count(fv));

    // Every patch is a disk and its embedding covers the canonical triangle
    // once: all triangles turn the same way and their areas sum to its area.
    const PatchParameterization uv = parameterize_patches(side, p);
    std::vector<std::vector<int>> faces(f);
    for (int t = 0; t < int(side.patch.size()); ++t) faces[side.patch[t]].push_back(t);
    for (int t = 0; t < f; ++t) {
      ASSERT_FALSE(faces[t].empty());
      EXPECT_EQ(euler(side.mesh.triangles(), faces[t]), 1);
      double total = 0;
      int positive = 0, negative = 0;
      for (int face : faces[t]) {
        const Triangle& c = side.mesh.triangles()[face];
        const Vec2 x = uv.uv[t].at(c[1]) - uv.uv[t].at(c[0]), y = uv.uv[t].at(c[2]) - uv.uv[t].at(c[0]);
        const double area = 0.5 * (x.x() * y.y() - x.y() * y.x());
        total += area;
        (area > 0 ? positive : negative) += 1;
      }
      EXPECT_TRUE(positive == 0 || negative == 0) << positive << " / " << negative << " in patch " << t;
      EXPECT_NEAR(std::abs(total), std::sqrt(3.0) / 4, 1e-9);
    }
  }
}

class HigherGenusPartition : public ::testing::TestWithParam<Pair> {};

TEST_P(HigherGenusPartition, BaseTriangulationsAgreeAndPatchesEmbedBijectively) {
  const TriangleMesh a = read_mesh(shared_mesh(GetParam().a)), b = read_mesh(shared_mesh(GetParam().b));
  ConsistentPartition p = consistent_partition(a, b, {{0, 0}}, GetParam().genus);
  expect_consistent_partition(p, GetParam().genus);
}

// A mesh against its mirror image (turned to face outwards again), each
// feature onto its own mirror image: every triple of features turns the
// other way on B, so every tree path passes some feature on the other side
// than on A. Such paths wait, and the last ones joining two components are
// re-routed; the partition stays consistent (spot_low, 10 features,
// measured 43 paths put off, 4 of 5 laid at last re-routed).
TEST(ConsistentPartition, MirrorImagePathsArePutOffAndRerouted) {
  const TriangleMesh a = read_mesh(shared_mesh("genus0/spot_low.obj"));
  TriangleMesh b = a;
  for (Vec3& p : b.vertices) p.x() = -p.x();
  for (Triangle& t : b.triangles) std::swap(t[1], t[2]);
  std::vector<std::array<int, 2>> pairs;
  for (int v : farthest_points(a, 10)) pairs.push_back({v, v});
  ConsistentPartition p = consistent_partition(a, b, pairs, 0);
  EXPECT_GT(p.delayed_paths, 10);
  EXPECT_GT(p.rerouted_paths, 0);
  expect_consistent_partition(p, 0);
}

// Per base triangle: its share of the side's area.
std::vector<double> area_shares(const PartitionSide& side, int patches) {
  std::vector<double> share(patches, 0);
  double total = 0;
  for (int f = 0; f < int(side.patch.size()); ++f) {
    const Triangle& t = side.mesh.triangles()[f];
    const double area = 0.5 * (side.mesh.position(t[1]) - side.mesh.position(t[0]))
                                  .cross(side.mesh.position(t[2]) - side.mesh.position(t[0]))
                                  .norm();
    share[side.patch[f]] += area, total += area;
  }
  for (double& s : share) s /= total;
  return share;
}

// The kitten and the rocker arm partitioned from one pair: one base triangle
// covers 1.3 % of the kitten and 48 % of the rocker arm. Balancing moves the
// paths until every patch takes about the same share of both, and the
// partition stays consistent.
TEST(PatchBalance, KittenAndRockerArmPatchesTakeEqualShares) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/kitten.off"));
  const TriangleMesh b = read_mesh(shared_mesh("higher-genus/rocker-arm.obj"));
  ConsistentPartition p = consistent_partition(a, b, {{0, 0}}, 1);
  const int patches = int(p.triangles.size());
  const auto worst = [&] {
    const std::vector<double> sa = area_shares(p.sides[0], patches), sb = area_shares(p.sides[1], patches);
    double ratio = 1;
    for (int t = 0; t < patches; ++t) ratio = std::max({ratio, sa[t] / sb[t], sb[t] / sa[t]});
    return ratio;
  };
  const double before = worst();
  const std::vector<std::vector<int>> paths_before = {p.sides[0].paths.begin(), p.sides[0].paths.end()};
  const PatchBalance balance = balance_patch_areas(p, 4);
  EXPECT_GT(before, 5.0);
  EXPECT_NEAR(balance.worst_before, before, 1e-9);
  EXPECT_NEAR(balance.worst_after, worst(), 1e-9);
  EXPECT_NEAR(patch_area_ratio(p), worst(), 1e-9);
  EXPECT_LT(balance.worst_after, 1.5);
  EXPECT_GT(balance.retraced, 0);
  EXPECT_NE(p.sides[0].paths, paths_before);
  expect_consistent_partition(p, 1);
}

// A side's refined triangles that take over 1,000 times more of their
// patch's canonical triangle than of the patch's area: slivers the patch
// embedding blows up, where the map sends canonical area onto next to nothing.
int blown_up_triangles(PartitionSide& side, const ConsistentPartition& p) {
  const PatchParameterization uv = parameterize_patches(side, p);
  const auto area = [](const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); };
  std::vector<double> patch_area(p.triangles.size(), 0);
  for (int f = 0; f < int(side.patch.size()); ++f) {
    const Triangle& t = side.mesh.triangles()[f];
    patch_area[side.patch[f]] += area(side.mesh.position(t[0]), side.mesh.position(t[1]), side.mesh.position(t[2]));
  }
  int blown = 0;
  for (int f = 0; f < int(side.patch.size()); ++f) {
    const Triangle& t = side.mesh.triangles()[f];
    const auto& at = uv.uv[side.patch[f]];
    const auto lift = [&](int v) { return Vec3(at.at(v).x(), at.at(v).y(), 0); };
    const double canonical = area(lift(t[0]), lift(t[1]), lift(t[2])) / (std::sqrt(3.0) / 4);
    const double share = area(side.mesh.position(t[0]), side.mesh.position(t[1]), side.mesh.position(t[2])) /
                         patch_area[side.patch[f]];
    blown += canonical > 1000 * share;
  }
  return blown;
}

// Feline - skull with the benchmark's 4 axis-extreme pairs: balancing laid
// retraced paths as close as 1e-5 of an edge along the patches' other
// sides, and the embeddings blew the slivers between them up (5,665 such
// triangles of the feline, 772 of the skull; the map's mean symmetric
// Dirichlet was 114,185). Retraced paths keep clear of the other paths
// (measured 4 and 0).
TEST(PatchBalance, RetracedPathsPinchNoPatch) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/feline.off"));
  const TriangleMesh b = read_mesh(shared_mesh("higher-genus/skull.obj"));
  ConsistentPartition p = consistent_partition(a, b, {{25240, 1883}, {14907, 2010}, {2, 50}, {49860, 5112}}, 2);
  const PatchBalance balance = balance_patch_areas(p, 4);
  EXPECT_GT(balance.retraced, 0);
  EXPECT_LT(balance.worst_after, balance.worst_before);
  expect_consistent_partition(p, 2);
  for (PartitionSide& side : p.sides) EXPECT_LT(blown_up_triangles(side, p), 50);
}

// Mean distance, relative to the source's diagonal, of its vertices from
// their round trip (the reverse map's images interpolated at the images).
double round_trip(const TriangleMesh& source, const TriangleMesh& target, const std::vector<SurfacePoint>& there,
                  const std::vector<Vec3>& back_on_source) {
  double sum = 0;
  for (std::size_t v = 0; v < source.vertices.size(); ++v) {
    const SurfacePoint& p = there[v];
    Vec3 back = Vec3::Zero();
    for (int k = 0; k < 3; ++k) back += p.barycentric[k] * back_on_source[target.triangles[p.triangle][k]];
    sum += (back - source.vertices[v]).norm();
  }
  return sum / double(source.vertices.size()) / diagonal(source);
}

class HigherGenusMap : public ::testing::TestWithParam<Pair> {};

TEST_P(HigherGenusMap, ValidExactAndInvertible) {
  const TriangleMesh a = read_mesh(shared_mesh(GetParam().a)), b = read_mesh(shared_mesh(GetParam().b));
  const std::vector<FeaturePair> given{{3, 5}, {int(a.vertices.size()) / 2, int(b.vertices.size()) / 3}};
  const IntersurfaceResult r = intersurface_map(a, b, given);
  EXPECT_EQ(r.genus, GetParam().genus);
  ASSERT_GE(r.features.size(), 2u);
  EXPECT_EQ(r.features[0].a, 3);
  EXPECT_EQ(r.features[1].b, int(b.vertices.size()) / 3);
  EXPECT_EQ(r.added_features, int(r.features.size()) - 2);
  EXPECT_EQ(r.base_vertices - r.base_triangles / 2, 2 - 2 * r.genus);  // V - E + F with E = 3F/2
  expect_valid_points(r.a_to_b, b);
  expect_valid_points(r.b_to_a, a);
  expect_exact_features(r, a, b);
  // Both directions invert each other (up to interpolation over a triangle).
  EXPECT_LT(round_trip(a, b, r.a_to_b, r.b_on_a), kRoundTrip);
  EXPECT_LT(round_trip(b, a, r.b_to_a, r.a_on_b), kRoundTrip);
  EXPECT_TRUE(std::isfinite(r.distortion_a_to_b.symmetric_dirichlet));
  EXPECT_TRUE(std::isfinite(r.distortion_b_to_a.symmetric_dirichlet));
  EXPECT_EQ(r.map_flipped, 0);  // the map itself folds nowhere, whatever its vertex sampling does
}

TEST_P(HigherGenusMap, ZeroFeaturesGetAValidMap) {
  const TriangleMesh a = read_mesh(shared_mesh(GetParam().a)), b = read_mesh(shared_mesh(GetParam().b));
  const IntersurfaceResult r = intersurface_map(a, b, {});
  EXPECT_GE(r.added_features, 1);
  expect_valid_points(r.a_to_b, b);
  expect_valid_points(r.b_to_a, a);
  expect_exact_features(r, a, b);
  EXPECT_LT(round_trip(a, b, r.a_to_b, r.b_on_a), kRoundTrip);
  EXPECT_EQ(r.map_flipped, 0);
}

// With balanced patches the kitten - rocker arm map is far less distorted
// over most of both surfaces (summed medians measured 330 -> 29), and still
// a valid, invertible map with exact features; without rounds the partition
// stays as traced.
TEST(HigherGenusMap, BalancedPatchesLowerTheMediansOfDifferentShapes) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/kitten.off"));
  const TriangleMesh b = read_mesh(shared_mesh("higher-genus/rocker-arm.obj"));
  // One first pair for both (screening starts would pick each its own).
  IntersurfaceOptions balanced, as_traced;
  balanced.starts = as_traced.starts = 1;
  as_traced.balance_rounds = 0;
  const IntersurfaceResult plain = intersurface_map(a, b, {}, as_traced), r = intersurface_map(a, b, {}, balanced);
  const auto median = [](const IntersurfaceResult& x) {
    return x.distortion_a_to_b.median_symmetric_dirichlet + x.distortion_b_to_a.median_symmetric_dirichlet;
  };
  EXPECT_FALSE(plain.balanced_patches);
  EXPECT_GT(plain.patch_area_ratio, 5.0);
  EXPECT_TRUE(r.balanced_patches);
  EXPECT_LT(r.patch_area_ratio, 1.5);
  EXPECT_LT(median(r), median(plain) / 3);
  expect_valid_points(r.a_to_b, b);
  expect_valid_points(r.b_to_a, a);
  expect_exact_features(r, a, b);
  EXPECT_LT(round_trip(a, b, r.a_to_b, r.b_on_a), kRoundTrip);
  EXPECT_LT(round_trip(b, a, r.b_to_a, r.a_on_b), kRoundTrip);
}

// A partition as traced whose patches' area shares lie more than
// max_traced_ratio apart is not mapped, only the balanced one. On torus -
// knot that drops 7 of the screening's 16 maps as traced (ratios up to 52)
// and none that counts: the starts rank alike and the same map is kept,
// the one through the partition as traced from the torus's side (ratio
// 2.5). A limit below that ratio drops that one too.
TEST(HigherGenusMap, TracedPartitionsTooUnbalancedAreNotMapped) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/torus.obj"));
  const TriangleMesh b = read_mesh(shared_mesh("higher-genus/knot.obj"));
  IntersurfaceOptions every;
  every.max_traced_ratio = std::numeric_limits<double>::infinity();
  const IntersurfaceResult r = intersurface_map(a, b, {}), all = intersurface_map(a, b, {}, every);
  EXPECT_EQ(r.start_median_dirichlet, all.start_median_dirichlet);
  EXPECT_FALSE(r.balanced_patches);
  EXPECT_FALSE(all.balanced_patches);
  EXPECT_EQ(r.moved_b, all.moved_b);
  expect_same_images(r, all);
  IntersurfaceOptions strict;
  strict.max_traced_ratio = 2;
  EXPECT_TRUE(intersurface_map(a, b, {}, strict).balanced_patches);
}

// Without features, the partition is traced from eight spread first pairs,
// each mapped with its patches' areas matched but without the local sweeps,
// and the least distorted is optimized: kitten - rocker arm's third start
// pairs the surfaces far better than the first alone (summed medians
// measured 19.8 -> 13.2, folded samples 903 -> 326). Restarts optimize more
// of the screened starts. Given features, there is no first pair to vary.
TEST(HigherGenusMap, FirstPairsAreScreenedAndTheLeastDistortedOptimized) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/kitten.off"));
  const TriangleMesh b = read_mesh(shared_mesh("higher-genus/rocker-arm.obj"));
  const auto median = [](const IntersurfaceResult& x) {
    return x.distortion_a_to_b.median_symmetric_dirichlet + x.distortion_b_to_a.median_symmetric_dirichlet;
  };
  const auto folds = [](const IntersurfaceResult& x) { return x.distortion_a_to_b.flipped + x.distortion_b_to_a.flipped; };
  const IntersurfaceResult r = intersurface_map(a, b, {});
  IntersurfaceOptions first_only;
  first_only.starts = 1;
  const IntersurfaceResult first = intersurface_map(a, b, {}, first_only);
  ASSERT_EQ(r.start_median_dirichlet.size(), std::size_t(IntersurfaceOptions{}.starts));
  EXPECT_TRUE(first.start_median_dirichlet.empty());
  EXPECT_TRUE(r.restart_median_dirichlet.empty());
  EXPECT_LT(median(r), 0.8 * median(first));
  EXPECT_LT(folds(r), folds(first) / 2);
  expect_valid_points(r.a_to_b, b);
  expect_valid_points(r.b_to_a, a);
  expect_exact_features(r, a, b);
  EXPECT_LT(round_trip(a, b, r.a_to_b, r.b_on_a), kRoundTrip);

  const TriangleMesh torus = read_mesh(shared_mesh("higher-genus/torus.obj"));
  const TriangleMesh knot = read_mesh(shared_mesh("higher-genus/knot.obj"));
  IntersurfaceOptions two;
  two.restarts = 2;
  const IntersurfaceResult restarted = intersurface_map(torus, knot, {}, two);
  ASSERT_EQ(restarted.restart_median_dirichlet.size(), 2u);
  const auto& medians = restarted.restart_median_dirichlet;
  EXPECT_DOUBLE_EQ(median(restarted), *std::min_element(medians.begin(), medians.end()));
  const IntersurfaceResult given = intersurface_map(torus, knot, {{0, 0}}, two);
  EXPECT_TRUE(given.start_median_dirichlet.empty());
  EXPECT_TRUE(given.restart_median_dirichlet.empty());
  IntersurfaceOptions none;
  none.starts = 0;
  EXPECT_THROW(intersurface_map(torus, knot, {}, none), InvalidInput);
}

// The screened start kept is optimized on the partitions its screening
// traced, not traced again: exactly the map that start gives when every
// start is optimized from scratch. Of its first six starts eight - skull
// keeps the fifth, neither the first nor the last traced, so partitions of
// the wrong start would show (the sweeps cut short: only sameness counts
// here).
TEST(HigherGenusMap, ScreenedStartIsOptimizedOnItsOwnPartitions) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/eight.off"));
  const TriangleMesh b = read_mesh(shared_mesh("higher-genus/skull.obj"));
  IntersurfaceOptions quick;
  quick.starts = 6;
  quick.optimize_sweeps = 2;
  quick.cross_sweeps = 2;
  const IntersurfaceResult screened = intersurface_map(a, b, {}, quick);
  IntersurfaceOptions every = quick;
  every.restarts = 6;  // as many as the starts: each optimized, none screened
  const IntersurfaceResult all = intersurface_map(a, b, {}, every);
  ASSERT_EQ(screened.start_median_dirichlet.size(), 6u);
  ASSERT_EQ(all.restart_median_dirichlet.size(), 6u);
  EXPECT_TRUE(all.start_median_dirichlet.empty());
  const std::vector<double>& ranked = screened.start_median_dirichlet;
  const auto kept = std::min_element(ranked.begin(), ranked.end()) - ranked.begin();
  ASSERT_EQ(kept, 4);
  EXPECT_EQ(screened.distortion_a_to_b.median_symmetric_dirichlet + screened.distortion_b_to_a.median_symmetric_dirichlet,
            all.restart_median_dirichlet[kept]);
  EXPECT_EQ(screened.distortion_a_to_b.flipped + screened.distortion_b_to_a.flipped, all.restart_flipped[kept]);
}

// A mesh and a copy with its vertices listed in another order: the same
// partition, so the map is the identity, an isometry without flips.
TEST(HigherGenusMap, ReorderedCopyMapsOntoItself) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/torus.obj"));
  const int n = int(a.vertices.size());
  std::vector<int> new_index(n);
  for (int v = 0; v < n; ++v) new_index[v] = int((std::int64_t(v) * 7919 + 13) % n);  // 7919 is prime, n = 2304
  TriangleMesh b;
  b.vertices.resize(n);
  for (int v = 0; v < n; ++v) b.vertices[new_index[v]] = a.vertices[v];
  for (const Triangle& t : a.triangles) b.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  const IntersurfaceResult r = intersurface_map(a, b, {});
  for (int v = 0; v < n; ++v) EXPECT_LT((r.a_on_b[v] - a.vertices[v]).norm(), 1e-9 * diagonal(a));
  EXPECT_NEAR(r.distortion_a_to_b.symmetric_dirichlet, 4, 1e-6);
  EXPECT_NEAR(r.distortion_b_to_a.symmetric_dirichlet, 4, 1e-6);
  EXPECT_EQ(r.distortion_a_to_b.flipped, 0);
  EXPECT_EQ(r.distortion_b_to_a.flipped, 0);
}

// The torus against a stretched (1.5, 1, 0.7), re-indexed copy: the true
// correspondence is known. B's paths and cycles follow A's in A's frame
// (intersurface/path_guide.h), so the handles match: without pairs 5.2 %
// mean error (31 % before: the automatic pair and the cycles did not
// correspond), with 16 farthest-point pairs 2.4 % (3.0 % before).
TEST(HigherGenusMap, StretchedCopyMatchesItsHandles) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/torus.obj"));
  const int n = int(a.vertices.size());
  std::vector<int> new_index;
  const TriangleMesh b = stretched_copy(a, Vec3(1.5, 1.0, 0.7), new_index);
  for (const auto& [count, tolerance] : {std::pair{0, 0.1}, {16, 0.04}}) {
    std::vector<FeaturePair> pairs;
    if (count > 0)
      for (int v : farthest_points(a, count)) pairs.push_back({v, new_index[v]});
    const IntersurfaceResult r = intersurface_map(a, b, pairs);
    double error = 0;
    for (int v = 0; v < n; ++v) error += (r.a_on_b[v] - b.vertices[new_index[v]]).norm();
    error /= n * diagonal(b);
    std::printf("  %d pairs: mean error %.2f %% of the diagonal\n", count, 100 * error);
    EXPECT_LT(error, tolerance) << count << " pairs";
  }
}

// A copy stood up from y-up to z-up, as meshes from different tools come:
// with no pairs B's frame is turned onto A's principal axes
// (intersurface/path_guide.h), so the first pair and the handles still
// correspond: 2.1 % mean error, 15.8 % when B was not turned.
TEST(HigherGenusMap, CopyStoodUpFromYUpToZUpMatchesWithoutPairs) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/kitten.off"));
  const int n = int(a.vertices.size());
  std::vector<int> new_index;
  TriangleMesh b = stretched_copy(a, Vec3(1.5, 1.0, 0.7), new_index);
  for (Vec3& p : b.vertices) p = Vec3(p.x(), -p.z(), p.y());
  IntersurfaceOptions options;
  options.starts = 1;
  const IntersurfaceResult r = intersurface_map(a, b, {}, options);
  double error = 0;
  for (int v = 0; v < n; ++v) error += (r.a_on_b[v] - b.vertices[new_index[v]]).norm();
  error /= n * diagonal(b);
  std::printf("  kitten stood up: mean error %.2f %% of the diagonal\n", 100 * error);
  EXPECT_LT(error, 0.04);
  expect_valid_points(r.a_to_b, b);
  expect_valid_points(r.b_to_a, a);
}

// Genus 3 and 4 (2g = 6 and 8 non-separating paths) against stretched,
// bent, re-indexed copies of themselves, 12 farthest-point true pairs: the
// bases agree (V - E + F = 2 - 2g), the map is bijective with the pairs
// exact, and the handles match. Measured mean errors 1.1 % (genus3) and
// 1.6 % (fertility) of the diagonal; 3 % admits no handle mapped onto
// another (the torus's handles unmatched were 31 % off, see above).
TEST(HigherGenusMap, GenusThreeAndFourMatchTheirBentCopies) {
  for (const auto& [file, genus] : {std::pair{"higher-genus/genus3.off", 3}, {"higher-genus/fertility.off", 4}}) {
    const TriangleMesh a = read_mesh(shared_mesh(file));
    std::vector<int> new_index;
    TriangleMesh b = stretched_copy(a, Vec3(1.5, 1.0, 0.7), new_index);
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : a.vertices) centre += p / double(a.vertices.size());
    double size = 0;
    for (const Vec3& p : a.vertices) size = std::max(size, (p - centre).cwiseAbs().maxCoeff());
    for (int v = 0; v < int(a.vertices.size()); ++v)
      b.vertices[new_index[v]].y() += 0.3 * size * std::pow((a.vertices[v].x() - centre.x()) / size, 2);
    std::vector<FeaturePair> pairs;
    for (int v : farthest_points(a, 12)) pairs.push_back({v, new_index[v]});
    const IntersurfaceResult r = intersurface_map(a, b, pairs);
    EXPECT_EQ(r.genus, genus) << file;
    EXPECT_EQ(r.base_vertices - r.base_triangles / 2, 2 - 2 * genus) << file;
    EXPECT_EQ(r.map_flipped, 0) << file;
    expect_valid_points(r.a_to_b, b);
    expect_valid_points(r.b_to_a, a);
    expect_exact_features(r, a, b);
    double error = 0;
    for (int v = 0; v < int(a.vertices.size()); ++v) error += (r.a_on_b[v] - b.vertices[new_index[v]]).norm();
    error /= double(a.vertices.size()) * diagonal(b);
    std::printf("  %s: %d base vertices, mean error %.2f %% of the diagonal\n", file, r.base_vertices, 100 * error);
    EXPECT_LT(error, 0.03) << file;
  }
}

// `mesh` without the triangles around each of `centres` (and without those
// vertices): one hole per centre.
TriangleMesh with_holes(const TriangleMesh& mesh, const std::vector<int>& centres) {
  std::vector<int> index(mesh.vertices.size(), 0);
  for (int c : centres) index[c] = -1;
  TriangleMesh out;
  for (int v = 0; v < int(mesh.vertices.size()); ++v)
    if (index[v] >= 0) index[v] = int(out.vertices.size()), out.vertices.push_back(mesh.vertices[v]);
  for (const Triangle& t : mesh.triangles)
    if (index[t[0]] >= 0 && index[t[1]] >= 0 && index[t[2]] >= 0)
      out.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
  return out;
}

// Per boundary edge (u, v) of `mesh`, both orders.
std::set<std::pair<int, int>> boundary_edges(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
  std::set<std::pair<int, int>> edges;
  for (const auto& [e, n] : count)
    if (n == 1) edges.insert(e), edges.insert({e.second, e.first});
  return edges;
}

// Thesis 5.4, boundaries: a torus with two holes against its stretched,
// re-indexed copy. Every rim vertex lands on the other mesh's rim (on a
// boundary edge, nothing on the third corner), both ways, and the map
// follows the true correspondence.
TEST(HigherGenusMap, HolesMapOntoHolesAndRimsOntoRims) {
  const TriangleMesh torus = read_mesh(shared_mesh("higher-genus/torus.obj"));
  const std::vector<int> far = farthest_points(torus, 2);
  const TriangleMesh a = with_holes(torus, far);
  std::vector<int> new_index;
  const TriangleMesh b = stretched_copy(a, Vec3(1.5, 1.0, 0.7), new_index);
  const int n = int(a.vertices.size());
  for (const auto& [count, tolerance] : {std::pair{0, 0.1}, {16, 0.03}}) {
    std::vector<FeaturePair> pairs;
    for (int v : farthest_points(a, count)) pairs.push_back({v, new_index[v]});
    const IntersurfaceResult r = intersurface_map(a, b, pairs);
    EXPECT_EQ(r.genus, 1);
    EXPECT_EQ(r.map_flipped, 0);
    expect_valid_points(r.a_to_b, b);
    expect_valid_points(r.b_to_a, a);
    expect_exact_features(r, a, b);
    for (const auto& [source, target, images] :
         {std::tuple<const TriangleMesh&, const TriangleMesh&, const std::vector<SurfacePoint>&>{a, b, r.a_to_b},
          {b, a, r.b_to_a}}) {
      const auto rim_source = boundary_edges(source), rim_target = boundary_edges(target);
      std::set<int> on_rim, on_target_rim;
      for (const auto& e : rim_source) on_rim.insert(e.first);
      for (const auto& e : rim_target) on_target_rim.insert(e.first);
      EXPECT_EQ(on_rim.size(), 12u);  // two rings of 6
      for (int v : on_rim) {
        const SurfacePoint& p = images[v];
        const Triangle& t = target.triangles[p.triangle];
        bool lands = false;  // on a boundary edge (nothing on the third corner) or at a rim vertex
        for (int k = 0; k < 3; ++k)
          lands |= (p.barycentric[k] < 1e-9 && rim_target.count({t[(k + 1) % 3], t[(k + 2) % 3]})) ||
                   (p.barycentric[k] > 1 - 1e-9 && on_target_rim.count(t[k]));
        EXPECT_TRUE(lands) << "rim vertex " << v << " lands off the other rim";
      }
    }
    double error = 0;
    for (int v = 0; v < n; ++v) error += (r.a_on_b[v] - b.vertices[new_index[v]]).norm();
    error /= n * diagonal(b);
    std::printf("  %d pairs: mean error %.2f %% of the diagonal\n", count, 100 * error);
    EXPECT_LT(error, tolerance) << count << " pairs";  // unrelated vertices: about 30 %
  }
  // A pair joining a rim vertex to a vertex on no rim: refused.
  std::set<int> rim;
  for (const auto& e : boundary_edges(a)) rim.insert(e.first);
  int inner = 0;
  while (rim.count(inner)) ++inner;
  EXPECT_THROW(intersurface_map(a, b, {{*rim.begin(), new_index[inner]}}), InvalidInput);
  // As many holes on both, or a clear error.
  const TriangleMesh one_hole = with_holes(torus, {far[0]});
  EXPECT_THROW(
      {
        try {
          intersurface_map(a, one_hole, {});
        } catch (const InvalidInput& e) {
          EXPECT_NE(std::string(e.what()).find("A has 2 holes, B has 1"), std::string::npos) << e.what();
          throw;
        }
      },
      InvalidInput);
}

// Corner images, both ways, of a copy with its vertices reordered, its
// triangles turned the other way and a stray vertex no triangle uses: the
// map is the identity, so each corner's image is its own point next to it,
// in the same triangle.
TEST(HigherGenusMap, CornerImagesOfAReversedCopyAreTheirOwnPoints) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/torus.obj"));
  const int n = int(a.vertices.size());
  const auto moved = [n](int v) { return int((std::int64_t(v) * 7919 + 13) % n); };
  TriangleMesh b;
  b.vertices.resize(n);
  for (int v = 0; v < n; ++v) b.vertices[moved(v)] = a.vertices[v];
  for (const Triangle& t : a.triangles) b.triangles.push_back({moved(t[0]), moved(t[2]), moved(t[1])});
  b.vertices.push_back(Vec3(9, 9, 9));
  IntersurfaceOptions options;
  options.corner_images = true;
  const IntersurfaceResult r = intersurface_map(a, b, {}, options);
  const int triangles = int(a.triangles.size());
  ASSERT_EQ(r.a_corners_to_b.size(), 3u * triangles);
  ASSERT_EQ(r.b_corners_to_a.size(), 3u * triangles);
  expect_valid_points(r.a_corners_to_b, b);
  expect_valid_points(r.b_corners_to_a, a);
  const std::vector<Vec3> on_b = surface_positions(b, r.a_corners_to_b), on_a = surface_positions(a, r.b_corners_to_a);
  for (int t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(r.a_corners_to_b[3 * t + k].triangle, t);
      EXPECT_EQ(r.b_corners_to_a[3 * t + k].triangle, t);
      EXPECT_LT((on_b[3 * t + k] - nudged_corner(a, t, k)).norm(), 1e-9 * diagonal(a));
      EXPECT_LT((on_a[3 * t + k] - nudged_corner(b, t, k)).norm(), 1e-9 * diagonal(a));
    }
}

// A stretched copy of the torus with 16 identical vertex pairs: each
// corner's image lies next to its vertex's image, and near the corner's own
// point on the copy (the same weights in the same triangle) as closely as
// the vertices' images lie to their own.
TEST(HigherGenusMap, CornerImagesOfAStretchedCopyLandNextToTheirCorners) {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/torus.obj"));
  TriangleMesh b = a;
  for (Vec3& p : b.vertices) p = p.cwiseProduct(Vec3(1.5, 1.0, 0.7));
  std::vector<FeaturePair> pairs;
  for (int v : farthest_points(a, 16)) pairs.push_back({v, v});
  IntersurfaceOptions options;
  options.corner_images = true;
  const IntersurfaceResult r = intersurface_map(a, b, pairs, options);
  expect_valid_points(r.a_corners_to_b, b);
  expect_valid_points(r.b_corners_to_a, a);
  const std::vector<double> ab_offsets = corner_offsets(r.a_corners_to_b, a, b, r.a_on_b, diagonal(b));
  const std::vector<double> ba_offsets = corner_offsets(r.b_corners_to_a, b, a, r.b_on_a, diagonal(a));
  const double ab = *std::max_element(ab_offsets.begin(), ab_offsets.end());
  const double ba = *std::max_element(ba_offsets.begin(), ba_offsets.end());
  const auto far = [](const std::vector<double>& offsets) {
    return std::count_if(offsets.begin(), offsets.end(), [](double d) { return d > 0.002; });
  };
  double vertices = 0, corners = 0;
  for (std::size_t v = 0; v < a.vertices.size(); ++v) vertices += (r.a_on_b[v] - b.vertices[v]).norm();
  const std::vector<Vec3> on_b = surface_positions(b, r.a_corners_to_b);
  for (int t = 0; t < int(a.triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) corners += (on_b[3 * t + k] - nudged_corner(b, t, k)).norm();
  vertices /= double(a.vertices.size()) * diagonal(b);
  corners /= 3.0 * double(a.triangles.size()) * diagonal(b);
  std::printf("stretched torus: corner images at most %.5f / %.5f of the diagonal from their vertices' images; "
              "mean error %.4f (corners), %.4f (vertices); %ld / %ld of %zu corners farther than 0.002\n", ab, ba,
              corners, vertices, long(far(ab_offsets)), long(far(ba_offsets)), ab_offsets.size());
  // Measured: at most 0.6-1.1 % of the diagonal, a few corners where the map
  // stretches most farther than 0.2 %: 35 / 59 of 13,824 (session 47), 39 /
  // 87 once the patch embeddings' LU ordering changed, 42 / 71 with it and
  // partial pivoting. Those counts move with rounding alone.
  EXPECT_LT(ab, 0.015);
  EXPECT_LT(ba, 0.015);
  EXPECT_LT(far(ab_offsets), long(ab_offsets.size()) / 100);
  EXPECT_LT(far(ba_offsets), long(ba_offsets.size()) / 100);
  EXPECT_LT(corners, 0.05);
  EXPECT_LT(corners, vertices + 0.005);
}

INSTANTIATE_TEST_SUITE_P(Pairs, HigherGenusPartition, ::testing::ValuesIn(kPairs));
INSTANTIATE_TEST_SUITE_P(Pairs, HigherGenusMap, ::testing::ValuesIn(kPairs));

}  // namespace
}  // namespace cmaps
