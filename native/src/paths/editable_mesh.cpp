#include "paths/editable_mesh.h"

#include <algorithm>
#include <map>
#include <numeric>

#include "common/ring.h"
#include "consistent_maps/errors.h"

namespace cmaps {

EditableMesh::EditableMesh(const TriangleMesh& mesh)
    : input_vertices_(static_cast<int>(mesh.vertices.size())),
      positions_(mesh.vertices),
      origins_(mesh.vertices.size()),
      triangles_(mesh.triangles),
      input_triangle_(mesh.triangles.size()),
      vertex_faces_(mesh.vertices.size()) {
  std::iota(input_triangle_.begin(), input_triangle_.end(), 0);
  for (int v = 0; v < input_vertices_; ++v) origins_[v] = {{v, -1, -1}, {1, 0, 0}};
  for (int f = 0; f < static_cast<int>(triangles_.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles_[f][k], b = triangles_[f][(k + 1) % 3];
      vertex_faces_[a].push_back(f);
      auto [it, inserted] = edge_index_.emplace(key(a, b), edge_count());
      if (inserted) {
        edge_vertices_.push_back({std::min(a, b), std::max(a, b)});
        edge_faces_.push_back({f, -1});
      } else if (edge_faces_[it->second][1] < 0) {
        edge_faces_[it->second][1] = f;
      } else {
        throw TopologyError("mesh has an edge with more than two triangles");
      }
    }
  for (const auto& faces : edge_faces_)
    if (faces[1] < 0) throw TopologyError("mesh has a boundary edge");
  face_edges_.resize(triangles_.size());
  for (int f = 0; f < static_cast<int>(triangles_.size()); ++f) index_face_edges(f);
}

void EditableMesh::index_face_edges(int f) {
  for (int k = 0; k < 3; ++k) face_edges_[f][k] = edge(triangles_[f][k], triangles_[f][(k + 1) % 3]);
}

std::uint64_t EditableMesh::key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

int EditableMesh::edge(int a, int b) const {
  const auto it = edge_index_.find(key(a, b));
  return it == edge_index_.end() ? -1 : it->second;
}

std::vector<int> EditableMesh::ring(int v) const {
  std::vector<Triangle> star;
  for (int f : vertex_faces_[v]) star.push_back(triangles_[f]);
  return ring_around(v, star);
}

void EditableMesh::set_edge(int a, int b, int f0, int f1) {
  auto [it, inserted] = edge_index_.emplace(key(a, b), edge_count());
  if (inserted) {
    edge_vertices_.push_back({std::min(a, b), std::max(a, b)});
    edge_faces_.push_back({f0, f1});
  } else {
    edge_faces_[it->second] = {f0, f1};
  }
}

void EditableMesh::replace_edge_face(int a, int b, int old_face, int new_face) {
  auto& faces = edge_faces_[edge(a, b)];
  std::replace(faces.begin(), faces.end(), old_face, new_face);
}

int EditableMesh::split_edge(int e, double at) {
  const auto [a, b] = edge_vertices_[e];
  const auto [f1, f2] = edge_faces_[e];
  const int m = vertex_count();
  positions_.push_back((1 - at) * positions_[a] + at * positions_[b]);
  // The new vertex's input-surface coordinates: blend those of a and b, which
  // always lie in one input triangle (edges never leave input triangles).
  std::map<int, double> combination;
  for (const auto& [v, share] : {std::pair<int, double>{a, 1 - at}, {b, at}})
    for (int k = 0; k < 3; ++k)
      if (origins_[v].vertices[k] >= 0) combination[origins_[v].vertices[k]] += share * origins_[v].weights[k];
  if (combination.size() > 3) throw Error("internal error: Steiner vertex outside one input triangle");
  InputPoint point;
  int slot = 0;
  for (const auto& [vertex, weight] : combination) {
    point.vertices[slot] = vertex;
    point.weights[slot++] = weight;
  }
  origins_.push_back(point);
  vertex_faces_.emplace_back();

  // Each triangle (x, y, opposite) with edge x -> y = {a, b} becomes
  // (x, m, opposite) in place plus a new (m, y, opposite).
  int new_faces[2];
  int opposite[2];
  int from[2], to[2];
  const int faces[2] = {f1, f2};
  for (int i = 0; i < 2; ++i) {
    Triangle& t = triangles_[faces[i]];
    int k = 0;
    while (!((t[k] == a && t[(k + 1) % 3] == b) || (t[k] == b && t[(k + 1) % 3] == a))) ++k;
    from[i] = t[k];
    to[i] = t[(k + 1) % 3];
    opposite[i] = t[(k + 2) % 3];
    new_faces[i] = static_cast<int>(triangles_.size());
    t[(k + 1) % 3] = m;
    triangles_.push_back({m, to[i], opposite[i]});
    input_triangle_.push_back(input_triangle_[faces[i]]);
    // `to` leaves the old triangle for the new one; m and the opposite vertex join it.
    auto& to_faces = vertex_faces_[to[i]];
    std::replace(to_faces.begin(), to_faces.end(), faces[i], new_faces[i]);
    vertex_faces_[opposite[i]].push_back(new_faces[i]);
    vertex_faces_[m].push_back(faces[i]);
    vertex_faces_[m].push_back(new_faces[i]);
    replace_edge_face(to[i], opposite[i], faces[i], new_faces[i]);
    set_edge(m, opposite[i], faces[i], new_faces[i]);
  }
  // The two halves of the old edge: from[0]-m lies in faces[0] and in the new triangle of side 1.
  edge_index_.erase(key(a, b));
  set_edge(from[0], m, faces[0], new_faces[1]);
  set_edge(m, to[0], new_faces[0], faces[1]);
  // The old edge's id stays unused from now on.
  edge_vertices_[e] = {-1, -1};
  edge_faces_[e] = {-1, -1};
  face_edges_.resize(triangles_.size());
  for (int i = 0; i < 2; ++i) index_face_edges(faces[i]), index_face_edges(new_faces[i]);
  return m;
}

}  // namespace cmaps
