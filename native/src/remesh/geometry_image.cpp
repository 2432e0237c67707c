#include "consistent_maps/geometry_image.h"

#include <string>

#include "consistent_maps/errors.h"
#include "remesh/image_size.h"

namespace cmaps {

GeometryImage geometry_image(const OctahedralGrid& grid, const std::vector<Vec3>& vertex_values) {
  if (vertex_values.size() != grid.sphere.size())
    throw InvalidInput("geometry image: " + std::to_string(vertex_values.size()) + " values for a grid of " +
                       std::to_string(grid.sphere.size()) + " vertices");
  GeometryImage image;
  image.n = grid.n;
  image.pixels.reserve(grid.pixel_vertex.size());
  for (int v : grid.pixel_vertex) image.pixels.push_back(vertex_values[v]);
  return image;
}

std::vector<Vec3> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> normals(mesh.vertices.size(), Vec3::Zero());
  for (const Triangle& t : mesh.triangles) {
    // The unnormalized cross product weights each triangle by its area.
    const Vec3 n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    for (int c : t) normals[c] += n;
  }
  for (Vec3& n : normals)
    if (n.norm() > 0) n.normalize();
  return normals;
}

TriangleMesh geometry_image_mesh(const GeometryImage& image) {
  check_image_size(image);
  const OctahedralGrid grid = octahedral_grid(image.n);
  TriangleMesh mesh;
  mesh.vertices.resize(grid.sphere.size());
  std::vector<bool> seen(grid.sphere.size(), false);
  for (size_t p = 0; p < image.pixels.size(); ++p) {
    const int v = grid.pixel_vertex[p];
    if (!seen[v]) mesh.vertices[v] = image.pixels[p], seen[v] = true;
  }
  mesh.triangles = grid.triangles;
  return mesh;
}

}  // namespace cmaps
