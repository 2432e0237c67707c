// Meshes with holes (thesis 3.5): constrained and consistent maps with each
// hole ringed by features, hole boundaries on great-circle arcs.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/sphere_locator.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::diagonal;
using test::hole_and_interior_features;
using test::loops_of;
using test::shared_mesh;

// Largest distance of a boundary vertex from the great-circle arc between
// the two features that enclose it along its loop (the plane distance, and
// +1 when it lies outside the arc's span).
double boundary_arc_error(const TriangleMesh& mesh, const std::vector<int>& features, const std::vector<Vec3>& sphere) {
  std::set<int> is_feature(features.begin(), features.end());
  double worst = 0;
  for (const auto& loop : loops_of(mesh)) {
    std::vector<size_t> at;
    for (size_t j = 0; j < loop.size(); ++j)
      if (is_feature.count(loop[j])) at.push_back(j);
    for (size_t a = 0; a < at.size(); ++a) {
      const Vec3 &p = sphere[loop[at[a]]], &q = sphere[loop[at[(a + 1) % at.size()]]];
      const Vec3 n = p.cross(q).normalized();
      for (size_t j = (at[a] + 1) % loop.size(); j != at[(a + 1) % at.size()]; j = (j + 1) % loop.size()) {
        const Vec3& x = sphere[loop[j]];
        double e = std::abs(x.dot(n));
        if (p.cross(x).dot(n) < 0 || x.cross(q).dot(n) < 0) e += 1;
        worst = std::max(worst, e);
      }
    }
  }
  return worst;
}

void expect_valid_map(const TriangleMesh& mesh, const std::vector<int>& features, const ConstrainedResult& r) {
  EXPECT_EQ(r.report.flipped, 0);
  EXPECT_EQ(r.report.degenerate, 0);
  EXPECT_LT(r.max_constraint_error, 1e-12);
  EXPECT_LT(boundary_arc_error(mesh, features, r.sphere), 1e-9);
  const int vertices = static_cast<int>(mesh.vertices.size() + r.steiner.size());
  for (const Triangle& t : r.triangles)
    for (int v : t) ASSERT_TRUE(v >= 0 && v < vertices);
  EXPECT_GE(r.triangles.size(), mesh.triangles.size());
  EXPECT_EQ(r.holes, static_cast<int>(loops_of(mesh).size()));
  // Together with the holes' fans, the map covers the sphere once.
  const ParameterizedSurface closed = parameterized_surface(mesh, r, true);
  EXPECT_NO_THROW(SphereLocator(closed.sphere, closed.surface.triangles));
}

TEST(ConstrainedHoles, FaceDiskWithOneHole) {
  const TriangleMesh mesh = read_mesh(shared_mesh("boundary/face_disk.off"));
  ASSERT_EQ(loops_of(mesh).size(), 1u);
  const std::vector<int> features = hole_and_interior_features(mesh, 4, 4);
  const ConstrainedResult r = constrained_spherical_parameterization(mesh, features, {});
  expect_valid_map(mesh, features, r);
  std::cout << "face_disk: efficiency " << r.report.efficiency << ", steiner " << r.steiner.size() << "\n";
  EXPECT_GT(r.report.efficiency, 0.2);
}

TEST(ConstrainedHoles, BunnyWithFiveHoles) {
  // The file keeps the vertices of the removed faces; maps need every vertex
  // on a triangle, so drop the unreferenced ones.
  const TriangleMesh file = read_mesh(shared_mesh("boundary/bunny_holes.obj"));
  TriangleMesh mesh;
  std::vector<int> index(file.vertices.size(), -1);
  for (Triangle t : file.triangles) {
    for (int& v : t) {
      if (index[v] < 0) {
        index[v] = static_cast<int>(mesh.vertices.size());
        mesh.vertices.push_back(file.vertices[v]);
      }
      v = index[v];
    }
    mesh.triangles.push_back(t);
  }
  ASSERT_EQ(loops_of(mesh).size(), 5u);
  const std::vector<int> features = hole_and_interior_features(mesh, 3, 4);
  SphereOptions options;
  options.effort = 0;
  const ConstrainedResult r = constrained_spherical_parameterization(mesh, features, {}, options);
  expect_valid_map(mesh, features, r);
  std::cout << "bunny_holes: efficiency " << r.report.efficiency << "\n";
}

TEST(ConstrainedHoles, HolesNeedThreeFeaturesEach) {
  const TriangleMesh mesh = read_mesh(shared_mesh("boundary/face_disk.off"));
  std::vector<int> features = hole_and_interior_features(mesh, 2, 4);
  try {
    constrained_spherical_parameterization(mesh, features, {});
    ADD_FAILURE() << "accepted a hole with 2 features";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("hole 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ringed by 2 features"), std::string::npos) << e.what();
  }
}

std::vector<ConsistentMember> faces() {
  std::vector<ConsistentMember> members;
  for (const char* name : {"neutral", "smile", "surprise", "disgust"})
    members.push_back({read_mesh(shared_mesh(std::string("sets/faces/") + name + ".ply")), {}});
  const std::vector<int> chosen = hole_and_interior_features(members.front().mesh, 4, 6);
  for (auto& m : members) m.features = chosen;
  return members;
}

TEST(ConsistentHoles, FacesWithTwoHolesMatchTheirKnownCorrespondence) {
  const auto members = faces();
  ASSERT_EQ(loops_of(members[0].mesh).size(), 2u);
  ConsistentOptions options;
  options.grid = 32;
  const ConsistentResult r = consistent_spherical_parameterization(members, options);
  ASSERT_EQ(r.members.size(), members.size());
  for (size_t i = 0; i < members.size(); ++i) {
    expect_valid_map(members[i].mesh, members[i].features, r.members[i]);
    for (size_t k = 0; k < members[i].features.size(); ++k)
      EXPECT_LT((r.members[i].sphere[members[i].features[k]] - r.feature_locations[k]).norm(), 1e-15);
  }
  // Vertex i of the first face mapped onto each other face through the sphere.
  for (size_t j = 1; j < members.size(); ++j) {
    const ParameterizedSurface pb = parameterized_surface(members[j].mesh, r.members[j], true);
    const SphereLocator locator(pb.sphere, pb.surface.triangles);
    const auto mapped = locator.interpolate(pb.surface.vertices, locator.locate_all(r.members[0].sphere, 2), 2);
    double sum = 0;
    for (size_t v = 0; v < members[0].mesh.vertices.size(); ++v)
      sum += (mapped[v] - members[j].mesh.vertices[v]).norm();
    const double error = sum / members[0].mesh.vertices.size() / diagonal(members[j].mesh);
    std::cout << "faces: member " << j << " mean error " << 100 * error << " % of the diagonal, efficiency "
              << r.members[j].report.efficiency << "\n";
    EXPECT_LT(error, 0.03) << j;
  }
  // Consistent remeshes: one connectivity, holes left open, ending on each
  // member's own boundary: every vertex of a remesh edge that only one
  // triangle uses lies on a boundary edge of the input.
  const ConsistentRemesh remesh = consistent_remesh(members, r, 32);
  std::map<std::pair<int, int>, int> edge_uses;
  for (const Triangle& t : remesh.triangles)
    for (int k = 0; k < 3; ++k) ++edge_uses[std::minmax(t[k], t[(k + 1) % 3])];
  std::set<int> rim;
  for (const auto& [edge, uses] : edge_uses)
    if (uses == 1) rim.insert(edge.first), rim.insert(edge.second);
  EXPECT_GT(rim.size(), 20u);
  for (size_t i = 0; i < members.size(); ++i) {
    const TriangleMesh& mesh = members[i].mesh;
    double worst = 0;
    for (int v : rim) {
      const Vec3& x = remesh.positions[i][v];
      double nearest = std::numeric_limits<double>::infinity();
      for (const std::vector<int>& loop : loops_of(mesh))
        for (size_t k = 0; k < loop.size(); ++k) {
          const Vec3 &a = mesh.vertices[loop[k]], &b = mesh.vertices[loop[(k + 1) % loop.size()]];
          const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
          nearest = std::min(nearest, (a + t * (b - a) - x).norm());
        }
      worst = std::max(worst, nearest);
    }
    EXPECT_LT(worst, 1e-9 * diagonal(mesh)) << "member " << i;
  }
  const int in_hole = static_cast<int>(std::count(remesh.in_hole.begin(), remesh.in_hole.end(), 1));
  EXPECT_GT(in_hole, 0);
  EXPECT_LT(remesh.triangles.size(), 8u * 32 * 32);
  for (const Triangle& t : remesh.triangles)
    for (int v : t) EXPECT_FALSE(remesh.in_hole[v]);
  for (size_t i = 0; i < members.size(); ++i)
    for (size_t k = 0; k < members[i].features.size(); ++k)
      EXPECT_LT((remesh.positions[i][remesh.feature_vertices[k]] - members[i].mesh.vertices[members[i].features[k]])
                    .norm(),
                1e-9 * diagonal(members[i].mesh));
}

TEST(ConsistentHoles, FeaturesMustRingCorrespondingHoles) {
  auto members = faces();
  members.resize(2);
  // On mesh 1 the first hole feature and the last (interior) one swap: 4
  // features still ring that hole there, but not the same ones as on mesh 0.
  std::swap(members[1].features.front(), members[1].features.back());
  try {
    consistent_spherical_parameterization(members);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("ring a hole on mesh"), std::string::npos) << e.what();
  }
  members = faces();
  members.resize(2);
  members[1].features[0] = members[1].features[1] = -1;  // 2 of 4 left on that hole
  try {
    consistent_spherical_parameterization(members);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 1: hole"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cmaps
