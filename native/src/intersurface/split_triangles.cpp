#include "intersurface/split_triangles.h"

#include <algorithm>
#include <utility>

namespace cmaps {

SplitTriangles split_triangles(const PartitionSide& side) {
  const EditableMesh& mesh = side.mesh;
  // Per input triangle: its pieces (edge splits never cross input edges, so
  // its input vertices are the pieces' corners below input_vertex_count()).
  std::vector<std::vector<int>> pieces(side.input_triangles);
  for (int f = 0; f < int(mesh.triangles().size()); ++f)
    if (mesh.input_triangle(f) < side.input_triangles) pieces[mesh.input_triangle(f)].push_back(f);
  SplitTriangles split;
  split.of_vertex.resize(mesh.vertex_count());
  for (const std::vector<int>& faces : pieces) {
    if (faces.size() < 2) continue;
    std::vector<int> corners;
    Vec3 normal = Vec3::Zero();
    for (int f : faces) {
      const Triangle& t = mesh.triangles()[f];
      normal += (mesh.position(t[1]) - mesh.position(t[0])).cross(mesh.position(t[2]) - mesh.position(t[0]));
      for (int v : t)
        if (v < mesh.input_vertex_count() && std::find(corners.begin(), corners.end(), v) == corners.end())
          corners.push_back(v);
    }
    if (corners.size() != 3) continue;
    Triangle t{corners[0], corners[1], corners[2]};
    const Vec3 &a = mesh.position(t[0]), &b = mesh.position(t[1]), &c = mesh.position(t[2]);
    if ((b - a).cross(c - a).dot(normal) < 0) std::swap(t[1], t[2]);
    for (int v : t) split.of_vertex[v].push_back(int(split.corners.size()));
    split.corners.push_back(t);
    split.shape.push_back(source_triangle({mesh.position(t[0]), mesh.position(t[1]), mesh.position(t[2])}));
  }
  return split;
}

std::vector<std::int8_t> along_paths(const PartitionSide& side) {
  const EditableMesh& mesh = side.mesh;
  std::vector<char> on_path(mesh.vertex_count(), 0);
  for (const auto& path : side.paths)
    for (int v : path) on_path[v] = 1;
  std::vector<int> patch(side.input_triangles, -1);
  std::vector<std::int8_t> along(side.input_triangles, 0);
  for (int f = 0; f < int(mesh.triangles().size()); ++f) {
    const int t = mesh.input_triangle(f);
    if (t >= side.input_triangles) continue;
    if (patch[t] < 0) patch[t] = side.patch[f];
    if (patch[t] != side.patch[f]) along[t] = 2;
    for (int v : mesh.triangles()[f])
      if (v < mesh.input_vertex_count() && on_path[v] && along[t] == 0) along[t] = 1;
  }
  return along;
}

}  // namespace cmaps
