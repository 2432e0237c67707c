// Shared helpers for the native tests: paths to the shared meshes, scratch
// files, and tiny meshes built in code.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps::test {

inline std::string shared_mesh(const std::string& relative) {
  return std::string(CMAPS_SHARED_MESHES) + "/" + relative;
}

// A scratch file path unique to the running test, removed by the caller's OS temp cleanup.
inline std::string scratch_path(const std::string& suffix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string("cmaps_") + info->test_suite_name() + "_" + info->name();
  std::replace(name.begin(), name.end(), '/', '_');  // parameterized tests have '/' in their names
  return ::testing::TempDir() + name + suffix;
}

inline std::string write_text(const std::string& suffix, const std::string& text) {
  const std::string path = scratch_path(suffix);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Regular tetrahedron, outward (counter-clockwise) orientation.
inline TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertices = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.triangles = {{{0, 1, 2}}, {{0, 3, 1}}, {{0, 2, 3}}, {{1, 3, 2}}};
  return m;
}

// Octahedron, outward orientation: 6 vertices, 8 triangles.
inline TriangleMesh octahedron() {
  TriangleMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{{0, 2, 4}}, {{2, 1, 4}}, {{1, 3, 4}}, {{3, 0, 4}},
                 {{2, 0, 5}}, {{1, 2, 5}}, {{3, 1, 5}}, {{0, 3, 5}}};
  return m;
}

// Well-spread vertices: farthest-point sampling by Euclidean distance from vertex 0.
inline std::vector<int> farthest_points(const TriangleMesh& mesh, int count) {
  std::vector<int> chosen{0};
  std::vector<double> distance(mesh.vertices.size(), std::numeric_limits<double>::infinity());
  while (static_cast<int>(chosen.size()) < count) {
    for (size_t v = 0; v < distance.size(); ++v)
      distance[v] = std::min(distance[v], (mesh.vertices[v] - mesh.vertices[chosen.back()]).squaredNorm());
    chosen.push_back(static_cast<int>(std::max_element(distance.begin(), distance.end()) - distance.begin()));
  }
  return chosen;
}

// Boundary loops in order (each starting at its smallest vertex).
inline std::vector<std::vector<int>> loops_of(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> half;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) half[{t[k], t[(k + 1) % 3]}] = 1;
  std::map<int, int> next;
  for (const auto& [e, one] : half)
    if (!half.count({e.second, e.first})) next[e.second] = e.first;
  std::vector<std::vector<int>> loops;
  std::set<int> seen;
  for (const auto& [s, unused] : next) {
    if (seen.count(s)) continue;
    loops.emplace_back();
    for (int v = s; !seen.count(v); v = next.at(v)) {
      seen.insert(v);
      loops.back().push_back(v);
    }
  }
  return loops;
}

// `per_hole` features evenly along every loop, then `interior` more far from
// them and from each other.
inline std::vector<int> hole_and_interior_features(const TriangleMesh& mesh, int per_hole, int interior) {
  std::vector<int> chosen;
  std::set<int> boundary;
  for (const auto& loop : loops_of(mesh)) {
    for (int j = 0; j < per_hole; ++j) chosen.push_back(loop[j * loop.size() / per_hole]);
    boundary.insert(loop.begin(), loop.end());
  }
  std::vector<double> distance(mesh.vertices.size(), std::numeric_limits<double>::infinity());
  for (int c : chosen)
    for (size_t v = 0; v < distance.size(); ++v)
      distance[v] = std::min(distance[v], (mesh.vertices[v] - mesh.vertices[c]).squaredNorm());
  for (int i = 0; i < interior; ++i) {
    int best = -1;
    for (size_t v = 0; v < distance.size(); ++v)
      if (!boundary.count(int(v)) && (best < 0 || distance[v] > distance[best])) best = int(v);
    chosen.push_back(best);
    for (size_t v = 0; v < distance.size(); ++v)
      distance[v] = std::min(distance[v], (mesh.vertices[v] - mesh.vertices[best]).squaredNorm());
  }
  return chosen;
}

// Length of the bounding-box diagonal: the scale errors are measured against.
inline double diagonal(const TriangleMesh& mesh) {
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

// `mesh` scaled per axis, its vertex v renumbered new_index[v] = (7919 v + 13)
// mod n (a permutation for the meshes used): a copy with known correspondence.
inline TriangleMesh stretched_copy(const TriangleMesh& mesh, const Vec3& scale, std::vector<int>& new_index) {
  const int n = int(mesh.vertices.size());
  new_index.resize(n);
  for (int v = 0; v < n; ++v) new_index[v] = int((std::int64_t(v) * 7919 + 13) % n);
  TriangleMesh copy;
  copy.vertices.resize(n);
  for (int v = 0; v < n; ++v) copy.vertices[new_index[v]] = mesh.vertices[v].cwiseProduct(scale);
  for (const Triangle& t : mesh.triangles) copy.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  return copy;
}

}  // namespace cmaps::test
