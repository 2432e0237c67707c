// The transform that brings B into A's frame for the guided partition
// (intersurface/path_guide.h): exact when the pairs are related by an affine
// map or a similarity, the centroids and areas without pairs (B turned onto
// A's principal axes when that matches clearly closer, meshes posed alike
// left unturned), and the step factor 1 on A's path itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "intersurface/path_guide.h"
#include "test_support.h"

namespace cmaps {
namespace {

// A tetrahedron-like blob with some spread in every direction.
TriangleMesh blob() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {2, 0, 0.3}, {0.4, 1.5, 0}, {0.2, 0.3, 1.2}, {1.1, 0.9, 0.8}, {1.7, 1.2, -0.4}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TriangleMesh moved(const TriangleMesh& m, const Eigen::Affine3d& t) {
  TriangleMesh out = m;
  for (Vec3& p : out.vertices) p = t * p;
  return out;
}

TEST(PathGuide, RecoversAnAffineMapFromFourOrMorePairs) {
  const TriangleMesh a = blob();
  Eigen::Affine3d to_b = Eigen::Affine3d::Identity();
  to_b.linear() << 1.5, 0.2, 0, 0, 1.0, 0.1, 0.1, 0, 0.7;
  to_b.translation() = Vec3(3, -1, 2);
  const TriangleMesh b = moved(a, to_b);
  const PathGuide guide(a.vertices, b.vertices, a, b);
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_LT((guide.to_a(b.vertices[i]) - a.vertices[i]).norm(), 1e-12);
  // On A's path the factor is 1; it grows away from it.
  const std::vector<Vec3> path = {a.vertices[0], a.vertices[1], a.vertices[4]};
  const auto factor = guide.near(path);
  EXPECT_NEAR(factor(to_b * Vec3(1, 0, 0.15)), 1, 1e-12);  // on the first segment
  EXPECT_GT(factor(to_b * Vec3(1, 2, 0.15)), 1.5);
  EXPECT_EQ(guide.nearest(a.vertices[4], b.vertices), 4);
}

TEST(PathGuide, SimilarityFromThreePairsAndCentroidsWithout) {
  const TriangleMesh a = blob();
  const Eigen::Affine3d to_b =
      Eigen::Translation3d(1, 2, 3) * Eigen::AngleAxisd(0.7, Vec3(1, 2, 0.5).normalized()) * Eigen::Scaling(2.0);
  const TriangleMesh b = moved(a, to_b);
  const PathGuide three({a.vertices.begin(), a.vertices.begin() + 3}, {b.vertices.begin(), b.vertices.begin() + 3}, a,
                        b);
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_LT((three.to_a(b.vertices[i]) - a.vertices[i]).norm(), 1e-12);
  // No pairs: centroids onto each other, B scaled to A's area (no rotation).
  const PathGuide none({}, {}, a, b);
  Vec3 ca = Vec3::Zero(), cb = Vec3::Zero();
  for (size_t i = 0; i < a.vertices.size(); ++i) ca += a.vertices[i], cb += b.vertices[i];
  ca /= double(a.vertices.size()), cb /= double(b.vertices.size());
  EXPECT_LT((none.to_a(cb) - ca).norm(), 1e-12);
  EXPECT_NEAR((none.to_a(b.vertices[1]) - none.to_a(b.vertices[0])).norm(), (a.vertices[1] - a.vertices[0]).norm(),
              1e-12);
}

// Without pairs a mesh turned a quarter about one axis and tilted (the cow
// along y, as the horse lies, against itself along x) is turned back: every
// vertex lands on its own copy. Unturned, the cow stayed crosswise (worst
// vertex 0.95 and 0.77 of the diagonal away with 0 and 1 pairs).
TEST(PathGuide, TurnsBOntoAsPrincipalAxesWithoutPairs) {
  const TriangleMesh a = read_mesh(test::shared_mesh("genus0/cow.off"));
  const Eigen::Affine3d to_b = Eigen::Translation3d(5, -2, 1) * Eigen::AngleAxisd(0.2, Vec3::UnitX()) *
                               Eigen::AngleAxisd(EIGEN_PI / 2, Vec3::UnitZ()) * Eigen::Scaling(1.5);
  const TriangleMesh b = moved(a, to_b);
  const double diagonal = test::diagonal(a);
  for (const int pairs : {0, 1}) {
    const std::vector<Vec3> on_a(a.vertices.begin(), a.vertices.begin() + pairs),
        on_b(b.vertices.begin(), b.vertices.begin() + pairs);
    const PathGuide guide(on_a, on_b, a, b);
    double worst = 0;
    for (size_t i = 0; i < a.vertices.size(); ++i)
      worst = std::max(worst, (guide.to_a(b.vertices[i]) - a.vertices[i]).norm());
    EXPECT_LT(worst, 1e-3 * diagonal) << pairs << " pairs";
  }
}

// Meshes posed alike (poses of one cactus, expressions of one face, with
// shared vertex order) keep the unturned start: every vertex stays near its
// own copy (1.9 and 1.7 % of the diagonal on average; a quarter turn would
// put the cactus's arms on its trunk).
TEST(PathGuide, KeepsMeshesPosedAlikeUnturned) {
  for (const auto& [name_a, name_b] : std::vector<std::pair<std::string, std::string>>{
           {"sets/cactus/cactus0.ply", "sets/cactus/cactus3.ply"},
           {"sets/faces/neutral.ply", "sets/faces/surprise.ply"}}) {
    const TriangleMesh a = read_mesh(test::shared_mesh(name_a)), b = read_mesh(test::shared_mesh(name_b));
    const PathGuide guide({}, {}, a, b);
    double mean = 0;
    for (size_t i = 0; i < a.vertices.size(); ++i) mean += (guide.to_a(b.vertices[i]) - a.vertices[i]).norm();
    EXPECT_LT(mean / double(a.vertices.size()), 0.025 * test::diagonal(a)) << name_b;
  }
}


// The step factor's scan (started where the last point's nearest coarse
// segment lay, segments whose ball lies farther skipped) gives what the
// plain scan gives, to the last bit: the first nearest of the 64 coarse
// segments, then the nearest fine segment around it. A wavy path of 1,000
// points on the cow, asked about its own points (ties between segments
// meeting there), points walking along it, and points in random order.
TEST(PathGuide, TheStepFactorIsThePlainScans) {
  const TriangleMesh a = read_mesh(test::shared_mesh("genus0/cow.off"));
  const PathGuide guide({}, {}, a, a);
  std::vector<Vec3> path;
  for (int i = 0; i < 1000; ++i) {
    const double s = i / 999.0;
    path.push_back(Vec3(s, 0.2 * std::sin(40 * s), 0.1 * std::cos(25 * s)));
  }
  const auto squared_distance = [](const Vec3& p, const Vec3& from, const Vec3& to) {
    const Vec3 d = to - from;
    const double length = d.squaredNorm();
    const double t = length > 0 ? std::clamp((p - from).dot(d) / length, 0.0, 1.0) : 0.0;
    return (p - (from + t * d)).squaredNorm();
  };
  const int n = int(path.size()), step = (n + 63) / 64;
  const double scale = std::sqrt(surface_area(a));
  const auto plain = [&](const Vec3& on_b) {
    const Vec3 p = guide.to_a(on_b);
    int near = 0;
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i + 1 < n; i += step) {
      const double d = squared_distance(p, path[i], path[std::min(i + step, n - 1)]);
      if (d < nearest) nearest = d, near = i;
    }
    for (int i = std::max(0, near - step); i + 1 < n && i < near + 2 * step; ++i)
      nearest = std::min(nearest, squared_distance(p, path[i], path[i + 1]));
    return 1 + 4 * std::sqrt(nearest) / scale;  // path_guide.h: kPull = 4
  };
  std::vector<Vec3> asked = path;
  for (int i = 0; i < 3000; ++i) {
    const double s = i / 2999.0;
    asked.push_back(Vec3(s, 0.2 * std::sin(40 * s) + 0.05, 0.1 * std::cos(25 * s) - 0.03));
  }
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x(-0.5, 1.5), yz(-0.6, 0.6);
  for (int i = 0; i < 3000; ++i) asked.push_back(Vec3(x(random), yz(random), yz(random)));
  const auto factor = guide.near(path);
  for (std::size_t i = 0; i < asked.size(); ++i) ASSERT_EQ(factor(asked[i]), plain(asked[i])) << "point " << i;
}

}  // namespace
}  // namespace cmaps
