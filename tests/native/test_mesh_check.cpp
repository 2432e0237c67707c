// check_mesh counts and require_sphere_topology's message for each class of defect.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::octahedron;
using test::shared_mesh;
using test::tetrahedron;

// Expects require_sphere_topology to throw exactly type E with a message containing `text`.
template <class E>
void expect_rejected(const TriangleMesh& mesh, const std::string& text) {
  try {
    require_sphere_topology(mesh);
    FAIL() << "accepted a mesh that should fail with: " << text;
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(MeshCheck, Tetrahedron) {
  const MeshReport r = check_mesh(tetrahedron());
  EXPECT_EQ(r.vertices, 4);
  EXPECT_EQ(r.referenced_vertices, 4);
  EXPECT_EQ(r.faces, 4);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.boundary_loops, 0);
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_EQ(r.genus, 0);
  EXPECT_TRUE(r.manifold());
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(r.degenerate_faces + r.duplicate_faces + r.inconsistently_oriented_edges, 0);
  EXPECT_NO_THROW(require_sphere_topology(tetrahedron()));
  EXPECT_NO_THROW(require_sphere_topology(octahedron()));
}

TEST(MeshCheck, SummaryIsOneLine) {
  const std::string s = summarize(check_mesh(octahedron()));
  EXPECT_EQ(s, "6 vertices, 8 triangles, 1 component, closed, manifold, genus 0, Euler characteristic 2");
}

TEST(MeshCheck, EmptyMesh) { expect_rejected<InvalidInput>(TriangleMesh{}, "empty"); }

TEST(MeshCheck, NoTriangles) {
  TriangleMesh m = tetrahedron();
  m.triangles.clear();
  expect_rejected<InvalidInput>(m, "no triangles");
}

TEST(MeshCheck, OneTriangle) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{{0, 1, 2}}};
  expect_rejected<TopologyError>(m, "mesh has only 1 triangle;");
}

TEST(MeshCheck, OutOfRangeIndex) {
  TriangleMesh m = tetrahedron();
  m.triangles[3][1] = 99;
  EXPECT_EQ(check_mesh(m).out_of_range_indices, 1);
  expect_rejected<InvalidInput>(m, "triangle 3 refers to vertex 99 but the mesh has 4 vertices");
  m.triangles[3][1] = -1;
  expect_rejected<InvalidInput>(m, "refers to vertex -1");
}

TEST(MeshCheck, NonFiniteCoordinate) {
  TriangleMesh m = tetrahedron();
  m.vertices[2].z() = std::nan("");
  m.vertices[3].x() = INFINITY;
  EXPECT_EQ(check_mesh(m).non_finite_vertices, 2);
  expect_rejected<InvalidInput>(m, "vertex 2 has a non-finite coordinate");
}

TEST(MeshCheck, UnreferencedVertex) {
  TriangleMesh m = tetrahedron();
  m.vertices.push_back({5, 5, 5});
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.referenced_vertices, 4);
  EXPECT_EQ(r.genus, 0);  // topology is measured over referenced vertices
  expect_rejected<InvalidInput>(m, "1 unreferenced vertex (e.g. vertex 4)");
}

TEST(MeshCheck, RepeatedIndexIsDegenerate) {
  TriangleMesh m = tetrahedron();
  m.triangles.push_back({{0, 0, 1}});
  EXPECT_EQ(check_mesh(m).degenerate_faces, 1);
  expect_rejected<TopologyError>(m, "triangle 4 uses the same vertex twice");
}

TEST(MeshCheck, ZeroAreaTrianglesAreAllowed) {
  TriangleMesh m = tetrahedron();
  m.vertices[3] = 0.5 * (m.vertices[0] + m.vertices[1]);  // triangle (0, 3, 1) becomes a segment
  EXPECT_EQ(check_mesh(m).degenerate_faces, 1);
  EXPECT_NO_THROW(require_sphere_topology(m));
}

TEST(MeshCheck, TwoComponents) {
  TriangleMesh m = tetrahedron();
  for (const Vec3& p : tetrahedron().vertices) m.vertices.push_back(p + Vec3(5, 0, 0));
  for (const Triangle& t : tetrahedron().triangles) m.triangles.push_back({{t[0] + 4, t[1] + 4, t[2] + 4}});
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.genus, -1);
  expect_rejected<TopologyError>(m, "mesh has 2 components");
}

TEST(MeshCheck, DuplicateFace) {
  TriangleMesh m = tetrahedron();
  m.triangles.push_back({{2, 0, 1}});
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.duplicate_faces, 1);
  EXPECT_EQ(r.non_manifold_edges, 3);
  expect_rejected<TopologyError>(m, "1 duplicate triangle (e.g. triangle 4 repeats triangle 0)");
}

TEST(MeshCheck, NonManifoldEdge) {
  TriangleMesh m = tetrahedron();
  m.vertices.push_back({2, 0, 0});
  m.triangles.push_back({{1, 0, 4}});  // a fin on edge 0-1
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.non_manifold_edges, 1);
  EXPECT_FALSE(r.manifold());
  EXPECT_EQ(r.genus, -1);
  expect_rejected<TopologyError>(m, "1 non-manifold edge (e.g. edge 0-1 is shared by 3 triangles)");
}

// Glues two vertices of sphere.obj whose neighbourhoods are far apart: a pinched sphere.
TEST(MeshCheck, NonManifoldVertex) {
  TriangleMesh m = read_mesh(shared_mesh("genus0/sphere.obj"));
  const int keep = 0;
  int glue = 0;
  for (int v = 0; v < int(m.vertices.size()); ++v)
    if ((m.vertices[v] - m.vertices[keep]).norm() > (m.vertices[glue] - m.vertices[keep]).norm()) glue = v;
  const int last = int(m.vertices.size()) - 1;
  for (Triangle& t : m.triangles)
    for (int& v : t) v = v == glue ? keep : v == last ? glue : v;
  m.vertices[glue] = m.vertices[last];
  m.vertices.pop_back();
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.non_manifold_vertices, 1);
  EXPECT_EQ(r.non_manifold_edges, 0);
  EXPECT_EQ(r.components, 1);
  expect_rejected<TopologyError>(m, "1 non-manifold vertex (e.g. vertex 0)");
}

TEST(MeshCheck, Boundary) {
  TriangleMesh m = octahedron();
  m.triangles.pop_back();
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.genus, 0);
  expect_rejected<TopologyError>(m, "mesh has 1 boundary loop;");
}

TEST(MeshCheck, InconsistentOrientation) {
  TriangleMesh m = octahedron();
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  const MeshReport r = check_mesh(m);
  EXPECT_EQ(r.inconsistently_oriented_edges, 3);
  EXPECT_EQ(r.genus, 0);
  expect_rejected<TopologyError>(m, "3 inconsistently oriented edges");
}

TEST(MeshCheck, Genus) {
  expect_rejected<TopologyError>(read_mesh(shared_mesh("higher-genus/torus.obj")),
                                 "mesh has genus 1 (closed, 1 component); spherical parameterization needs genus 0");
}

TEST(MeshCheck, SharedBoundaryMeshesAreRejected) {
  expect_rejected<TopologyError>(read_mesh(shared_mesh("boundary/bunny_holes.obj")), "mesh has 5 boundary loops;");
  expect_rejected<TopologyError>(read_mesh(shared_mesh("boundary/face_disk.off")), "mesh has 1 boundary loop;");
}

TEST(MeshCheck, SharedInvalidMeshesAreRejected) {
  expect_rejected<TopologyError>(read_mesh(shared_mesh("invalid/dino_nonmanifold_edges.off")),
                                 "non-manifold edge");
  expect_rejected<TopologyError>(read_mesh(shared_mesh("invalid/teapot_newell_nonmanifold.obj")),
                                 "mesh has 4 components");
}

TEST(MeshCheck, LargeMeshIsFast) {
  const TriangleMesh m = read_mesh(shared_mesh("large/venus.off"));
  const auto start = std::chrono::steady_clock::now();
  const MeshReport r = check_mesh(m);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.genus, 0);
  EXPECT_LT(seconds, 5.0);  // O(n log n): well under a second in a release build
}

}  // namespace
}  // namespace cmaps
