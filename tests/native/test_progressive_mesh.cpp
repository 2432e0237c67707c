// Progressive mesh: simplification to a tetrahedron, exact refinement back to
// the input, locked vertices, path constraints, several geometries.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/progressive_mesh.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::shared_mesh;

// V - E + F of the current mesh, and whether every edge has two triangles.
std::pair<int, bool> euler_and_closed(const MeshRefinement& r) {
  const auto triangles = r.active_triangles();
  std::map<std::pair<int, int>, int> edges;
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) ++edges[std::minmax(t[k], t[(k + 1) % 3])];
  bool closed = true;
  for (const auto& [e, count] : edges) closed = closed && count == 2;
  return {r.active_vertex_count() - static_cast<int>(edges.size()) + static_cast<int>(triangles.size()), closed};
}

TEST(ProgressiveMesh, SimplifiesToTetrahedronAndRefinesExactly) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/bunny.off"));
  const ProgressiveMesh pm = build_progressive_mesh(mesh);
  EXPECT_EQ(pm.base_vertex_count(), 4);
  EXPECT_EQ(pm.splits.size(), mesh.vertices.size() - 4);
  MeshRefinement refinement(pm);
  EXPECT_EQ(refinement.active_triangles().size(), 4u);
  EXPECT_EQ(euler_and_closed(refinement), std::make_pair(2, true));
  while (refinement.has_next_split()) {
    const VertexSplit& s = refinement.apply_next_split();
    EXPECT_EQ(refinement.faces_of(s.removed).size(), refinement.ring(s.removed).size());
    if (refinement.splits_applied() % 500 == 0) EXPECT_EQ(euler_and_closed(refinement), std::make_pair(2, true));
  }
  EXPECT_EQ(refinement.triangles(), mesh.triangles);
  EXPECT_EQ(refinement.active_vertex_count(), static_cast<int>(mesh.vertices.size()));
  for (size_t f = 0; f < mesh.triangles.size(); ++f) EXPECT_TRUE(refinement.face_active(f));
}

TEST(ProgressiveMesh, RingIsCounterClockwise) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/spot_low.obj"));
  const ProgressiveMesh pm = build_progressive_mesh(mesh);
  MeshRefinement refinement(pm);
  while (refinement.has_next_split()) refinement.apply_next_split();
  // Every triangle (v, ring[i], ring[i+1]) of the ring must be a mesh triangle.
  std::set<Triangle> faces;
  for (Triangle t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      faces.insert(t);
      std::rotate(t.begin(), t.begin() + 1, t.end());
    }
  for (int v = 0; v < static_cast<int>(mesh.vertices.size()); v += 7) {
    const std::vector<int> ring = refinement.ring(v);
    for (size_t i = 0; i < ring.size(); ++i)
      EXPECT_TRUE(faces.count({v, ring[i], ring[(i + 1) % ring.size()]}));
  }
}

TEST(ProgressiveMesh, LockedVerticesSurvive) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/cow.off"));
  SimplificationOptions options;
  options.locked.assign(mesh.vertices.size(), 0);
  const std::vector<int> features{0, 100, 500, 1000, 1500, 2000, 2500, 2761};
  for (int v : features) options.locked[v] = 1;
  options.target_vertices = static_cast<int>(features.size());
  const ProgressiveMesh pm = build_progressive_mesh(mesh, options);
  for (const VertexSplit& s : pm.splits) EXPECT_FALSE(options.locked[s.removed]) << s.removed;
  for (int v : features) EXPECT_TRUE(pm.base_vertex_active[v]);
  // Locked vertices may block the last collapses, but never by much.
  EXPECT_LE(pm.base_vertex_count(), 2 * static_cast<int>(features.size()));
}

TEST(ProgressiveMesh, PathVerticesCollapseOnlyAlongTheirPath) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/spot_low.obj"));
  // A path: a chain of edges walked greedily from vertex 0.
  std::vector<int> path{mesh.triangles[0][0], mesh.triangles[0][1]};
  std::set<int> on_path(path.begin(), path.end());
  for (int step = 0; step < 30; ++step) {
    const int v = path.back();
    int next = -1;
    for (const Triangle& t : mesh.triangles)
      for (int k = 0; k < 3 && next < 0; ++k)
        if (t[k] == v && !on_path.count(t[(k + 1) % 3])) {
          // Avoid neighbours of earlier path vertices so the path stays simple.
          bool touches = false;
          for (const Triangle& u : mesh.triangles)
            for (int j = 0; j < 3; ++j)
              if (u[j] == t[(k + 1) % 3] && on_path.count(u[(j + 1) % 3]) && u[(j + 1) % 3] != v) touches = true;
          if (!touches) next = t[(k + 1) % 3];
        }
    if (next < 0) break;
    path.push_back(next);
    on_path.insert(next);
  }
  ASSERT_GE(path.size(), 10u);
  SimplificationOptions options;
  for (size_t i = 0; i + 1 < path.size(); ++i) options.path_edges.push_back({path[i], path[i + 1]});
  const ProgressiveMesh pm = build_progressive_mesh(mesh, options);
  EXPECT_TRUE(pm.base_vertex_active[path.front()]);
  EXPECT_TRUE(pm.base_vertex_active[path.back()]);
  for (const VertexSplit& s : pm.splits)
    if (on_path.count(s.removed)) EXPECT_TRUE(on_path.count(s.kept)) << s.removed << " -> " << s.kept;
  MeshRefinement refinement(pm);
  while (refinement.has_next_split()) refinement.apply_next_split();
  EXPECT_EQ(refinement.triangles(), mesh.triangles);
}

TEST(ProgressiveMesh, SeveralGeometries) {
  const TriangleMesh a = read_mesh(shared_mesh("sets/cactus/cactus0.ply"));
  const TriangleMesh b = read_mesh(shared_mesh("sets/cactus/cactus3.ply"));
  SimplificationOptions options;
  options.extra_geometries.push_back(b.vertices);
  const ProgressiveMesh pm = build_progressive_mesh(a, options);
  EXPECT_EQ(pm.base_vertex_count(), 4);
  options.extra_geometries.front().pop_back();
  EXPECT_THROW(build_progressive_mesh(a, options), InvalidInput);
}

TEST(ProgressiveMesh, CancelStops) {
  const TriangleMesh mesh = read_mesh(shared_mesh("genus0/bunny.off"));
  EXPECT_THROW(build_progressive_mesh(mesh, {}, [](double, const std::string&) { return false; }), Cancelled);
}

}  // namespace
}  // namespace cmaps
