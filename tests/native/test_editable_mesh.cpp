// The mesh that paths are traced on (paths/editable_mesh.h): its adjacency
// stays consistent as Steiner vertices split edges.
#include <gtest/gtest.h>

#include <random>

#include "consistent_maps/mesh_io.h"
#include "paths/editable_mesh.h"
#include "test_support.h"

namespace cmaps {
namespace {

// Every triangle's indexed edges are its own, and every edge names the two triangles holding it.
void expect_consistent(const EditableMesh& mesh) {
  for (int f = 0; f < int(mesh.triangles().size()); ++f) {
    const Triangle& t = mesh.triangles()[f];
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.face_edges(f)[k];
      ASSERT_EQ(e, mesh.edge(t[k], t[(k + 1) % 3])) << "triangle " << f << " edge " << k;
      const auto& faces = mesh.edge_faces(e);
      EXPECT_TRUE(faces[0] == f || faces[1] == f) << "edge " << e << " does not name triangle " << f;
    }
  }
}

TEST(EditableMesh, TrianglesIndexTheirEdgesThroughSplits) {
  EditableMesh mesh(read_mesh(test::shared_mesh("genus0/decimated-knight.off")));
  expect_consistent(mesh);
  std::mt19937 rng(3);
  for (int split = 0; split < 500; ++split) {
    int e;
    do e = std::uniform_int_distribution<int>(0, mesh.edge_count() - 1)(rng);
    while (mesh.edge_vertices(e)[0] < 0);  // an edge split before is gone
    const int before = int(mesh.triangles().size());
    const int m = mesh.split_edge(e, std::uniform_real_distribution<double>(0.2, 0.8)(rng));
    EXPECT_EQ(int(mesh.triangles().size()), before + 2);
    EXPECT_EQ(mesh.faces_of(m).size(), 4u);
  }
  expect_consistent(mesh);
}

}  // namespace
}  // namespace cmaps
