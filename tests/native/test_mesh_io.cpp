// Reading every supported format, keeping faces OpenMesh would reject, clear
// errors for unreadable input, and write -> read round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::shared_mesh;
using test::write_text;

// Expects read_mesh(path) to throw IoError whose message names the path and contains `reason`.
void expect_io_error(const std::string& path, const std::string& reason) {
  try {
    read_mesh(path);
    FAIL() << "no error for " << path;
  } catch (const IoError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MeshIo, ReadsObj) {
  const TriangleMesh m = read_mesh(shared_mesh("genus0/spot_low.obj"));
  EXPECT_EQ(m.vertices.size(), 829u);
  EXPECT_EQ(m.triangles.size(), 1654u);
}

TEST(MeshIo, ReadsOff) {
  const TriangleMesh m = read_mesh(shared_mesh("genus0/bunny.off"));
  EXPECT_EQ(m.vertices.size(), 3485u);
  EXPECT_EQ(m.triangles.size(), 6966u);
}

TEST(MeshIo, ReadsOffWithCommentInHeader) {
  const TriangleMesh m = read_mesh(shared_mesh("heads/maxplanck.off"));
  EXPECT_EQ(check_mesh(m).referenced_vertices, 12556);
  EXPECT_EQ(m.triangles.size(), 25108u);
}

TEST(MeshIo, ReadsBinaryPly) {
  const TriangleMesh m = read_mesh(shared_mesh("large/horse.ply"));
  EXPECT_EQ(m.vertices.size(), 48485u);
  EXPECT_EQ(m.triangles.size(), 96966u);
}

TEST(MeshIo, ReadsAsciiPly) {
  const std::string path = write_text(".ply",
                                      "ply\nformat ascii 1.0\nelement vertex 4\n"
                                      "property float x\nproperty float y\nproperty float z\n"
                                      "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
                                      "1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n"
                                      "3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n");
  const TriangleMesh m = read_mesh(path);
  ASSERT_EQ(m.vertices.size(), 4u);
  ASSERT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.triangles[1], (Triangle{0, 3, 1}));
  EXPECT_EQ(m.vertices[3], Vec3(-1, -1, 1));
}

TEST(MeshIo, ReadsAsciiStlMergingCorners) {
  const TriangleMesh tet = test::tetrahedron();
  std::string text = "solid tet\n";
  for (const Triangle& t : tet.triangles) {
    text += "facet normal 0 0 0\nouter loop\n";
    for (int v : t) {
      const Vec3& p = tet.vertices[v];
      text += "vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
    }
    text += "endloop\nendfacet\n";
  }
  text += "endsolid tet\n";
  const TriangleMesh m = read_mesh(write_text(".stl", text));
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_NO_THROW(require_sphere_topology(m));
}

TEST(MeshIo, FanTriangulatesPolygons) {
  const TriangleMesh m = read_mesh(write_text(".obj",
                                              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nv 3 1 0\n"
                                              "f 1 2 3 4\nf 2 5 6 7 3\n"));
  ASSERT_EQ(m.triangles.size(), 5u);
  EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(m.triangles[4], (Triangle{1, 6, 2}));
}

TEST(MeshIo, KeepsFacesOpenMeshWouldReject) {
  // Three triangles on edge 1-2: a complex edge a halfedge mesh cannot hold.
  const TriangleMesh m = read_mesh(write_text(".obj",
                                              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\n"
                                              "f 1 2 3\nf 2 1 4\nf 1 2 5\n"));
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(check_mesh(m).non_manifold_edges, 1);
}

TEST(MeshIo, KeepsOutOfRangeIndicesForTheCheck) {
  const TriangleMesh m = read_mesh(write_text(".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(check_mesh(m).out_of_range_indices, 1);
}

TEST(MeshIo, KeepsNonFiniteBinaryPlyCoordinates) {
  const std::string path = test::scratch_path(".ply");
  TriangleMesh tet = test::tetrahedron();
  tet.vertices[2].y() = std::nan("");
  write_mesh(path, tet);
  const TriangleMesh m = read_mesh(path);
  EXPECT_EQ(check_mesh(m).non_finite_vertices, 1);
}

TEST(MeshIo, MissingFileNamesThePath) { expect_io_error("/nonexistent/dir/mesh.obj", "no such file"); }

TEST(MeshIo, EmptyFile) { expect_io_error(write_text(".obj", ""), "empty"); }

TEST(MeshIo, UnknownExtension) { expect_io_error(write_text(".xyz", "1 2 3\n"), "unknown extension"); }

TEST(MeshIo, NoExtension) { expect_io_error(write_text("", "v 0 0 0\n"), "unknown extension"); }

TEST(MeshIo, Directory) { expect_io_error(::testing::TempDir(), "directory"); }

TEST(MeshIo, GarbagePly) { expect_io_error(write_text(".ply", "this is not a ply file\n"), "cannot read"); }

TEST(MeshIo, ObjNanCoordinatesAreKept) {
  const TriangleMesh m = read_mesh(write_text(".obj", "v 0 0 0\nv nan 0 0\nv 0 1 inf\nf 1 2 3\n"));
  ASSERT_EQ(m.vertices.size(), 3u);
  EXPECT_EQ(check_mesh(m).non_finite_vertices, 2);
}

TEST(MeshIo, ObjNegativeIndicesAndSlashes) {
  const TriangleMesh m = read_mesh(write_text(".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf -3/1 -2/1/1 3//1\n"));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
}

TEST(MeshIo, ObjRepeatedCornersAreKept) {
  const TriangleMesh m = read_mesh(write_text(".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n"));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(check_mesh(m).degenerate_faces, 1);
}

TEST(MeshIo, MalformedObjNamesTheLine) {
  expect_io_error(write_text(".obj", "v 0 0 0\nv 1 0\n"), "line 2: a vertex needs three numbers");
}

TEST(MeshIo, TruncatedOff) {
  expect_io_error(write_text(".off", "OFF\n4 4 0\n0 0 0\n1 0 0\n"), "file ends after 2 of 4 vertices");
}

TEST(MeshIo, OffWithCountsOnTheHeaderLineAndFaceColours) {
  const TriangleMesh m = read_mesh(write_text(".off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n"));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
}

TEST(MeshIo, ObjWithoutVertices) { expect_io_error(write_text(".obj", "# nothing here\n"), "no vertices"); }

class RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTrip, KeepsConnectivityOrderAndPrecision) {
  TriangleMesh original = test::octahedron();
  // Coordinates that single precision cannot hold: the writers must not round them.
  for (size_t i = 0; i < original.vertices.size(); ++i) original.vertices[i] *= 1.0 + 1e-12 * double(i + 1) / 3.0;
  const std::string path = test::scratch_path(GetParam());
  write_mesh(path, original);
  const TriangleMesh copy = read_mesh(path);
  ASSERT_EQ(copy.vertices.size(), original.vertices.size());
  EXPECT_EQ(copy.triangles, original.triangles);
  // OpenMesh's PLY reader hands over floats; the text formats keep every bit.
  const double tolerance = GetParam() == ".ply" ? 1e-7 : 0.0;
  for (size_t i = 0; i < original.vertices.size(); ++i)
    EXPECT_LE((copy.vertices[i] - original.vertices[i]).norm(), tolerance) << "vertex " << i;
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip, ::testing::Values(".obj", ".ply", ".off"),
                         [](const auto& test) { return test.param.substr(1); });

TEST(MeshIo, StlRoundTripKeepsTheSurface) {
  const std::string path = test::scratch_path(".stl");
  write_mesh(path, test::octahedron());
  const TriangleMesh copy = read_mesh(path);
  EXPECT_EQ(copy.vertices.size(), 6u);
  EXPECT_EQ(copy.triangles.size(), 8u);
  EXPECT_NO_THROW(require_sphere_topology(copy));
}

TEST(MeshIo, WriteRejectsUnknownExtension) {
  EXPECT_THROW(write_mesh(test::scratch_path(".xyz"), test::tetrahedron()), IoError);
}

TEST(MeshIo, WriteToMissingDirectoryFails) {
  try {
    write_mesh("/nonexistent/dir/out.obj", test::tetrahedron());
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/out.obj"), std::string::npos);
  }
}

}  // namespace
}  // namespace cmaps
