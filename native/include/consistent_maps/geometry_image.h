// Geometry images (Praun & Hoppe's flat octahedron): the values of an
// octahedral-grid remesh (positions, normals) laid out as an (n+1) x (n+1)
// image, written as a float64 .npy array of shape (n+1, n+1, 3) or as a
// 16-bit RGB PNG quantized to the values' bounding box (stored in a tEXt
// chunk named "cmaps_bbox" so the file reads back to geometry). Reading an
// image back and taking the octahedral grid's connectivity rebuilds the mesh.
#pragma once
#include <string>
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/octahedral_grid.h"

namespace cmaps {

struct GeometryImage {
  int n = 0;                 // (n+1) x (n+1) pixels, n even
  std::vector<Vec3> pixels;  // row-major: pixel (i, j) at i * (n+1) + j

  const Vec3& at(int i, int j) const { return pixels[static_cast<size_t>(i) * (n + 1) + j]; }
};

// Pixel (i, j) takes the value of grid vertex grid.vertex(i, j).
GeometryImage geometry_image(const OctahedralGrid& grid, const std::vector<Vec3>& vertex_values);

// Unit area-weighted vertex normals (zero for a vertex with only zero-area triangles).
std::vector<Vec3> vertex_normals(const TriangleMesh& mesh);

// The octahedral grid of the image's size with each vertex at its pixel's
// value (identified boundary pixels hold the same value; the first is used).
TriangleMesh geometry_image_mesh(const GeometryImage& image);

// Throw IoError when the file cannot be written or read or is not such an
// image; InvalidInput for an image whose pixel count does not match n.
void write_geometry_image_npy(const std::string& path, const GeometryImage& image);
GeometryImage read_geometry_image_npy(const std::string& path);  // '<f8' or '<f4', C order
void write_geometry_image_png(const std::string& path, const GeometryImage& image);
// Reads PNGs as written above: 16-bit RGB, stored (uncompressed) deflate
// blocks, no interlacing, filter type 0.
GeometryImage read_geometry_image_png(const std::string& path);

}  // namespace cmaps
