// A closed triangle mesh that can grow by edge splits (Steiner vertices),
// with the adjacency that path tracing needs: vertex -> triangles and an
// edge index with each edge's two triangles. Every vertex remembers where it
// lies on the input surface as a combination of at most three input vertices.
#pragma once
#include <array>
#include <unordered_map>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

struct InputPoint {
  std::array<int, 3> vertices{-1, -1, -1};  // input vertices (-1 = unused slot)
  std::array<double, 3> weights{0, 0, 0};   // barycentric weights, summing to 1
};

class EditableMesh {
 public:
  // Throws TopologyError unless every edge has exactly two triangles.
  explicit EditableMesh(const TriangleMesh& mesh);

  int vertex_count() const { return static_cast<int>(positions_.size()); }
  int input_vertex_count() const { return input_vertices_; }
  int edge_count() const { return static_cast<int>(edge_vertices_.size()); }
  const Vec3& position(int v) const { return positions_[v]; }
  const std::vector<Vec3>& positions() const { return positions_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<int>& faces_of(int v) const { return vertex_faces_[v]; }
  const std::array<int, 2>& edge_vertices(int e) const { return edge_vertices_[e]; }
  const std::array<int, 2>& edge_faces(int e) const { return edge_faces_[e]; }
  int edge(int a, int b) const;  // -1 when a and b are not adjacent
  // Triangle f's edges: k from its corner k to corner k + 1 (no lookup, for searches).
  const std::array<int, 3>& face_edges(int f) const { return face_edges_[f]; }
  std::vector<int> ring(int v) const;  // neighbours, counter-clockwise
  const InputPoint& surface_point(int v) const { return origins_[v]; }
  // The input triangle a triangle lies in (splits never cross input edges).
  int input_triangle(int f) const { return input_triangle_[f]; }

  // Inserts a vertex on edge e, `at` of the way from its first vertex
  // (edge_vertices(e)[0]) to its second, splitting its two triangles.
  int split_edge(int e, double at = 0.5);

 private:
  static std::uint64_t key(int a, int b);
  void set_edge(int a, int b, int f0, int f1);
  void replace_edge_face(int a, int b, int old_face, int new_face);
  void index_face_edges(int f);

  int input_vertices_;
  std::vector<Vec3> positions_;
  std::vector<InputPoint> origins_;
  std::vector<Triangle> triangles_;
  std::vector<int> input_triangle_;
  std::vector<std::vector<int>> vertex_faces_;
  std::unordered_map<std::uint64_t, int> edge_index_;
  std::vector<std::array<int, 2>> edge_vertices_, edge_faces_;
  std::vector<std::array<int, 3>> face_edges_;
};

}  // namespace cmaps
