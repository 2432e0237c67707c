// One mesh's side of a growing consistent partition
// (intersurface/partition_network.h): which side of a traced path a vertex
// lies on, what the swirl test of the partition compares between meshes.
#include <gtest/gtest.h>

#include <cmath>

#include "consistent_maps/mesh_io.h"
#include "intersurface/partition_network.h"
#include "test_support.h"

namespace cmaps {
namespace {

// On a sphere a shortest path runs near a great circle, so a vertex well
// off the circle, and whose foot on it lies well inside the path, is left
// of the path (walking from its first feature, outside up) exactly when it
// lies on the side of the circle's normal a x b. The path is traced once
// over vertices, once across a wall of blocked vertices it can only cross
// at edge midpoints (both kinds of node sort the vertices beside them).
TEST(PartitionSide, SidesOfAPathOnASphereFollowItsGreatCircle) {
  const TriangleMesh mesh = read_mesh(test::shared_mesh("genus0/sphere.obj"));
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : mesh.vertices) centre += p / double(mesh.vertices.size());
  const auto direction = [&](int v) { return Vec3((mesh.vertices[v] - centre).normalized()); };
  const auto nearest = [&](const Vec3& d) {
    int best = 0;
    for (int v = 0; v < int(mesh.vertices.size()); ++v)
      if (direction(v).dot(d) > direction(best).dot(d)) best = v;
    return best;
  };
  const int a = nearest(Vec3(1, 0, 0)), b = nearest(Vec3(-1, 1, 0).normalized());  // 135 degrees apart
  const Vec3 normal = direction(a).cross(direction(b)).normalized();
  const Vec3 across = normal.cross(direction(a));  // with direction(a), a frame of the circle's plane
  const double arc = std::atan2(direction(b).dot(across), direction(b).dot(direction(a)));
  const auto angle = [&](int v) { return std::atan2(direction(v).dot(across), direction(v).dot(direction(a))); };
  for (bool wall : {false, true}) {
    partition::Side side(mesh, int(mesh.triangles.size()));
    side.add_feature(a);
    side.add_feature(b);
    // The wall: a band, wider than an edge, around the great circle crossing the path's at its middle.
    const Vec3 tangent = normal.cross(std::cos(arc / 2) * direction(a) + std::sin(arc / 2) * across);
    if (wall)
      for (int v = 0; v < int(mesh.vertices.size()); ++v)
        if (std::abs(direction(v).dot(tangent)) < 0.25) side.blocked[v] = 1;
    const std::vector<int> nodes = side.trace(0, 1, nullptr, nullptr, wall, nullptr);
    ASSERT_GT(nodes.size(), 3u);
    const int vertices = side.mesh.vertex_count();
    int midpoints = 0;
    for (int node : nodes) midpoints += node >= vertices;
    if (wall) EXPECT_GT(midpoints, 0) << "the wall is crossed at edge midpoints";

    std::vector<int> queries;
    for (int v = 0; v < int(mesh.vertices.size()); ++v)
      if (std::abs(direction(v).dot(normal)) > 0.25 && std::abs(direction(v).dot(normal)) < 0.9 && angle(v) > 0.3 &&
          angle(v) < arc - 0.3)  // off the path, away from its ends and from the circle's poles (as near every point)
        queries.push_back(v);
    ASSERT_GT(queries.size(), 50u);
    const std::vector<int> sides = side.sides_of(nodes, vertices, queries);
    int wrong = 0;
    for (size_t q = 0; q < queries.size(); ++q)
      wrong += sides[q] != (direction(queries[q]).dot(normal) > 0 ? 1 : -1);
    EXPECT_EQ(wrong, 0) << (wall ? "across the wall" : "over vertices");
  }
}

// A vertex whose shortest route meets the path at one of its ends (beyond
// it, seen along the path) has no side.
TEST(PartitionSide, BeyondAnEndThereIsNoSide) {
  const TriangleMesh mesh = read_mesh(test::shared_mesh("genus0/sphere.obj"));
  int a = 0, b = 0, beyond = 0;  // lowest and highest x, and the vertex nearest a point past a
  for (int v = 0; v < int(mesh.vertices.size()); ++v) {
    if (mesh.vertices[v].x() < mesh.vertices[a].x()) a = v;
    if (mesh.vertices[v].x() > mesh.vertices[b].x()) b = v;
  }
  partition::Side side(mesh, int(mesh.triangles.size()));
  side.add_feature(a);
  side.add_feature(b);
  const std::vector<int> nodes = side.trace(0, 1, nullptr, nullptr, false, nullptr);
  // The far side of a's ring: a's neighbour farthest from the path's second vertex.
  double far = -1;
  for (int v : side.mesh.ring(a)) {
    const double d = (mesh.vertices[v] - mesh.vertices[nodes[1]]).norm();
    if (d > far) far = d, beyond = v;
  }
  EXPECT_EQ(side.sides_of(nodes, side.mesh.vertex_count(), {beyond})[0], 0);
}

}  // namespace
}  // namespace cmaps
