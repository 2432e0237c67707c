// OBJ texture coordinates and vertex colours: read in read_mesh's triangle
// order, written back, clear errors; transfer of both through a map.
#include <gtest/gtest.h>

#include "consistent_maps/attribute_transfer.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/obj_attributes.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::scratch_path;
using test::write_text;

// A square (quad, fan-triangulated) and a triangle, with colours, texture
// coordinates (the triangle's by negative index) and normals.
const char* const kAttributed =
    "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\nv 2 0 0 0.5 0.5 0.5\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
    "f 1/1/1 2/2/1 3/3/1 4/4/1\nf 2/-3 5/-2 3/-1\n";

TEST(ObjAttributes, ReadsInTheTriangleOrderOfReadMesh) {
  const std::string path = write_text(".obj", kAttributed);
  const TriangleMesh mesh = read_mesh(path);
  const ObjAttributes a = read_obj_attributes(path);
  ASSERT_EQ(mesh.triangles.size(), 3u);
  ASSERT_EQ(a.triangle_uvs.size(), 3u);
  EXPECT_EQ(a.uvs.size(), 4u);
  EXPECT_EQ(a.triangle_uvs[0], (std::array<int, 3>{0, 1, 2}));  // the fan of the quad, like read_mesh's
  EXPECT_EQ(a.triangle_uvs[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(a.triangle_uvs[2], (std::array<int, 3>{1, 2, 3}));
  ASSERT_EQ(a.colors.size(), 5u);
  EXPECT_EQ(a.colors[4], (std::array<double, 3>{0.5, 0.5, 0.5}));
}

TEST(ObjAttributes, PlainFilesHaveNone) {
  const ObjAttributes a = read_obj_attributes(write_text(".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_TRUE(a.uvs.empty() && a.triangle_uvs.empty() && a.colors.empty());
}

TEST(ObjAttributes, WritesWhatItReads) {
  const std::string path = write_text(".obj", kAttributed);
  const TriangleMesh mesh = read_mesh(path);
  const ObjAttributes a = read_obj_attributes(path);
  const std::string copy = scratch_path("_copy.obj");
  write_obj_with_attributes(copy, mesh, a);
  const ObjAttributes b = read_obj_attributes(copy);
  EXPECT_EQ(read_mesh(copy).triangles, mesh.triangles);
  EXPECT_EQ(b.uvs, a.uvs);
  EXPECT_EQ(b.triangle_uvs, a.triangle_uvs);
  EXPECT_EQ(b.colors, a.colors);
  EXPECT_THROW(write_obj_with_attributes(scratch_path(".ply"), mesh, a), IoError);
  ObjAttributes wrong = a;
  wrong.colors.pop_back();
  EXPECT_THROW(write_obj_with_attributes(copy, mesh, wrong), InvalidInput);
}

TEST(ObjAttributes, ClearErrors) {
  const auto expect = [](const std::string& text, const std::string& reason) {
    const std::string path = write_text(".obj", text);
    try {
      read_obj_attributes(path);
      FAIL() << "no error for " << text;
    } catch (const IoError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find(reason), std::string::npos) << message;
    }
  };
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
  expect(v + "vt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n", "line 7: the face has no texture coordinates but the face on line 6");
  expect(v + "vt 0 0\nf 1/1 2 3/1\n", "some corners of the face have texture coordinates and some not");
  expect(v + "vt 0 0\nf 1/1 2/2 3/1\n", "texture coordinate 2 does not exist (1 so far)");
  expect(v + "vt zero 0\n", "texture coordinates need one or two numbers");
  expect("v 0 0 0 1 1 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 2: the vertex has no colour but the vertex on line 1");
  EXPECT_THROW(read_obj_attributes(write_text(".off", "OFF\n0 0 0\n")), IoError);
  EXPECT_THROW(read_obj_attributes(scratch_path("_missing.obj")), IoError);
}

TEST(ObjAttributes, TransferInterpolatesVerticesAndCorners) {
  const std::string path = write_text(".obj", kAttributed);
  const TriangleMesh source = read_mesh(path);
  const ObjAttributes attributes = read_obj_attributes(path);
  // A one-triangle target whose vertices and corners land at known points of the source.
  const TriangleMesh target{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}}};
  IntersurfaceResult map;
  map.a_to_b = {{0, {1, 0, 0}}, {2, {0.5, 0.5, 0}}, {1, {0, 0.5, 0.5}}};
  map.a_corners_to_b = {map.a_to_b[0], {0, {0, 0.5, 0.5}}, map.a_to_b[2]};  // all in the quad's chart
  const ObjAttributes carried = transfer_obj_attributes(source, attributes, target, map);
  ASSERT_EQ(carried.colors.size(), 3u);
  EXPECT_EQ(carried.colors[0], (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(carried.colors[1], (std::array<double, 3>{0.25, 0.75, 0.25}));  // between vertices 2 and 5 (1-based)
  ASSERT_EQ(carried.triangle_uvs.size(), 1u);
  const auto uv = [&](int k) { return carried.uvs[carried.triangle_uvs[0][k]]; };
  EXPECT_EQ(uv(0), (std::array<double, 2>{0, 0}));
  EXPECT_EQ(uv(1), (std::array<double, 2>{1, 0.5}));
  EXPECT_EQ(uv(2), (std::array<double, 2>{0.5, 1}));
  map.a_corners_to_b.pop_back();
  EXPECT_THROW(transfer_obj_attributes(source, attributes, target, map), InvalidInput);
}

TEST(ObjAttributes, TransferContinuesTextureCoordinatesAcrossASeam) {
  // Two triangles whose texture coordinates jump by -1 in u across their shared edge (a cylinder's seam).
  const std::string path = write_text(".obj",
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                      "vt 0.9 0\nvt 1 0\nvt 0.9 1\nvt 0 0\nvt 0 1\nvt -0.1 1\n"
                                      "f 1/1 2/2 3/3\nf 2/4 4/5 3/6\n");
  const TriangleMesh source = read_mesh(path);
  const ObjAttributes attributes = read_obj_attributes(path);
  const TriangleMesh target{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}}};
  IntersurfaceResult map;
  map.a_to_b = {{0, {1, 0, 0}}, {0, {0, 1, 0}}, {0, {0, 0, 1}}};
  // The image straddles the seam: the first corner lands in the first triangle, the others in the second.
  map.a_corners_to_b = {{0, {1.0 / 3, 1.0 / 3, 1.0 / 3}}, {1, {0, 1, 0}}, {1, {1, 0, 0}}};
  const ObjAttributes carried = transfer_obj_attributes(source, attributes, target, map);
  const auto uv = [&](int k) { return carried.uvs[carried.triangle_uvs[0][k]]; };
  EXPECT_NEAR(uv(0)[0], 2.8 / 3, 1e-12);
  EXPECT_NEAR(uv(1)[0], 1.0, 1e-12) << "continued across the seam (0 in the second triangle's own chart)";
  EXPECT_NEAR(uv(1)[1], 1.0, 1e-12);
  EXPECT_NEAR(uv(2)[0], 1.0, 1e-12);
  EXPECT_NEAR(uv(2)[1], 0.0, 1e-12);
}

}  // namespace
}  // namespace cmaps
