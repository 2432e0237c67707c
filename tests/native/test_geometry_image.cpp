// Geometry images: octahedral remeshes laid out as images, written as .npy
// and 16-bit PNG, read back and rebuilt into the same mesh.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/octahedral_grid.h"
#include "consistent_maps/remesh.h"
#include "consistent_maps/spherical_parameterization.h"
#include "test_support.h"

namespace cmaps {
namespace {

using test::scratch_path;

struct Remesh {
  OctahedralGrid grid;
  TriangleMesh mesh;
};

const Remesh& spot_remesh() {
  static const Remesh r = [] {
    const TriangleMesh spot = read_mesh(test::shared_mesh("genus0/spot.obj"));
    Remesh out{octahedral_grid(32), {}};
    out.mesh = {resample(spot, spherical_parameterization(spot).sphere, out.grid.sphere), out.grid.triangles};
    return out;
  }();
  return r;
}

TEST(GeometryImage, PixelsFollowTheGridAndRebuildTheMesh) {
  const Remesh& r = spot_remesh();
  const GeometryImage image = geometry_image(r.grid, r.mesh.vertices);
  ASSERT_EQ(image.pixels.size(), 33u * 33u);
  EXPECT_EQ(image.at(0, 0), image.at(32, 32));  // corners fold onto one point
  EXPECT_EQ(image.at(0, 5), image.at(0, 27));   // mirrored boundary pixels
  const TriangleMesh rebuilt = geometry_image_mesh(image);
  EXPECT_EQ(rebuilt.vertices, r.mesh.vertices);
  EXPECT_EQ(rebuilt.triangles, r.mesh.triangles);
}

TEST(GeometryImage, NormalsPointOutwardOnTheGrid) {
  const OctahedralGrid grid = octahedral_grid(16);
  const std::vector<Vec3> normals = vertex_normals({grid.sphere, grid.triangles});
  for (size_t v = 0; v < normals.size(); ++v) {
    EXPECT_NEAR(normals[v].norm(), 1, 1e-12);
    EXPECT_GT(normals[v].dot(grid.sphere[v]), 0.99);
  }
}

TEST(GeometryImage, NpyRoundTripIsExact) {
  const Remesh& r = spot_remesh();
  for (const auto& values : {r.mesh.vertices, vertex_normals(r.mesh)}) {
    const GeometryImage image = geometry_image(r.grid, values);
    const std::string path = scratch_path(".npy");
    write_geometry_image_npy(path, image);
    const GeometryImage back = read_geometry_image_npy(path);
    EXPECT_EQ(back.n, image.n);
    EXPECT_EQ(back.pixels, image.pixels);
  }
}

TEST(GeometryImage, ReadsFloat32Npy) {
  // What numpy writes for np.zeros((3, 3, 3), np.float32) + 0.5, format 1.0.
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (3, 3, 3), }";
  header.append(117 - header.size(), ' ');
  header += '\n';
  std::string file = std::string("\x93NUMPY\x01\x00", 8) + char(header.size()) + '\0' + header;
  const float half = 0.5f;
  for (int k = 0; k < 27; ++k) file.append(reinterpret_cast<const char*>(&half), 4);
  const GeometryImage image = read_geometry_image_npy(test::write_text(".npy", file));
  EXPECT_EQ(image.n, 2);
  for (const Vec3& p : image.pixels) EXPECT_EQ(p, Vec3(0.5, 0.5, 0.5));
}

TEST(GeometryImage, PngRoundTripIsWithinQuantization) {
  const Remesh& r = spot_remesh();
  for (const auto& values : {r.mesh.vertices, vertex_normals(r.mesh)}) {
    const GeometryImage image = geometry_image(r.grid, values);
    const std::string path = scratch_path(".png");
    write_geometry_image_png(path, image);
    const GeometryImage back = read_geometry_image_png(path);
    ASSERT_EQ(back.n, image.n);
    Vec3 lo = values[0], hi = lo;
    for (const Vec3& v : values) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const Vec3 step = (hi - lo) / 65535;
    for (size_t p = 0; p < image.pixels.size(); ++p)
      for (int c = 0; c < 3; ++c) EXPECT_LE(std::abs(back.pixels[p][c] - image.pixels[p][c]), 0.5 * step[c] + 1e-15);
    // The bounding box itself is stored exactly.
    Vec3 back_lo = back.pixels[0], back_hi = back_lo;
    for (const Vec3& v : back.pixels) back_lo = back_lo.cwiseMin(v), back_hi = back_hi.cwiseMax(v);
    EXPECT_EQ(back_lo, lo);
    EXPECT_EQ(back_hi, hi);
    EXPECT_EQ(geometry_image_mesh(back).triangles, r.grid.triangles);
  }
}

TEST(GeometryImage, LargePngSpansSeveralDeflateBlocks) {
  const OctahedralGrid grid = octahedral_grid(128);  // 129 rows of 775 bytes: > 65535 bytes
  const GeometryImage image = geometry_image(grid, grid.sphere);
  const std::string path = scratch_path(".png");
  write_geometry_image_png(path, image);
  const GeometryImage back = read_geometry_image_png(path);
  for (size_t p = 0; p < image.pixels.size(); ++p) EXPECT_LT((back.pixels[p] - image.pixels[p]).norm(), 1e-4);
}

TEST(GeometryImage, RejectsBadFilesAndImages) {
  EXPECT_THROW(read_geometry_image_npy("/nonexistent/x.npy"), IoError);
  EXPECT_THROW(read_geometry_image_png("/nonexistent/x.png"), IoError);
  EXPECT_THROW(read_geometry_image_npy(test::write_text(".npy", "not numpy")), IoError);
  EXPECT_THROW(read_geometry_image_png(test::write_text(".png", "not a png")), IoError);

  const OctahedralGrid grid = octahedral_grid(4);
  const GeometryImage image = geometry_image(grid, grid.sphere);
  const std::string png = scratch_path(".png");
  write_geometry_image_png(png, image);
  std::string bytes;
  {
    std::ifstream in(png, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  bytes[bytes.size() / 2] ^= 0x55;  // inside the image data: the chunk CRC no longer matches
  EXPECT_THROW(read_geometry_image_png(test::write_text(".png", bytes)), IoError);
  EXPECT_THROW(read_geometry_image_png(test::write_text(".png", bytes.substr(0, 60))), IoError);

  const std::string npy = scratch_path(".npy");
  write_geometry_image_npy(npy, image);
  {
    std::ifstream in(npy, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  EXPECT_THROW(read_geometry_image_npy(test::write_text(".npy", bytes.substr(0, bytes.size() - 8))), IoError);

  GeometryImage wrong = image;
  wrong.pixels.pop_back();
  EXPECT_THROW(write_geometry_image_npy(scratch_path(".npy"), wrong), InvalidInput);
  EXPECT_THROW(write_geometry_image_png(scratch_path(".png"), wrong), InvalidInput);
  EXPECT_THROW(geometry_image_mesh(wrong), InvalidInput);
  EXPECT_THROW(geometry_image(grid, {Vec3::Zero()}), InvalidInput);
}

}  // namespace
}  // namespace cmaps
