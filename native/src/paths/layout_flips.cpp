#include "paths/layout_flips.h"

#include <algorithm>
#include <map>

#include "paths/mesh_search.h"

namespace cmaps {

int flip_layout_to_shorter_paths(const EditableMesh& mesh, const std::vector<int>& features,
                                 const std::vector<Vec3>& targets, std::vector<Triangle>& triangles,
                                 const std::vector<std::array<int, 2>>& fixed) {
  auto is_fixed = [&](int i, int j) {
    for (const auto& a : fixed)
      if ((a[0] == i && a[1] == j) || (a[0] == j && a[1] == i)) return true;
    return false;
  };
  std::vector<char> blocked(mesh.vertex_count(), 0);
  for (int v : features) blocked[v] = 1;
  std::map<std::pair<int, int>, double> cache;
  auto distance = [&](int i, int j) {
    const auto key = std::minmax(i, j);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    SearchRules rules;
    rules.blocked = &blocked;
    const double d = path_length(mesh, shortest_path(mesh, features[i], features[j], rules), mesh.vertex_count());
    return cache[key] = d;
  };
  auto valid = [&](int a, int b, int c) {
    const Vec3 &x = targets[a], &y = targets[b], &z = targets[c];
    return x.dot(y.cross(z)) > 1e-9 * (y - x).cross(z - x).norm();
  };

  int flips = 0;
  for (bool changed = true; changed && flips < 8 * static_cast<int>(triangles.size());) {
    changed = false;
    // Directed edge -> triangle, to find each arc's two triangles.
    std::map<std::pair<int, int>, int> owner;
    for (int f = 0; f < static_cast<int>(triangles.size()); ++f)
      for (int k = 0; k < 3; ++k) owner[{triangles[f][k], triangles[f][(k + 1) % 3]}] = f;
    for (int f = 0; f < static_cast<int>(triangles.size()) && !changed; ++f)
      for (int k = 0; k < 3 && !changed; ++k) {
        const int i = triangles[f][k], j = triangles[f][(k + 1) % 3], p = triangles[f][(k + 2) % 3];
        const int g = owner.at({j, i});
        const Triangle& other = triangles[g];
        const int q = other[0] != i && other[0] != j ? other[0] : other[1] != i && other[1] != j ? other[1] : other[2];
        if (p == q || is_fixed(i, j) || owner.count({p, q}) || !valid(p, i, q) || !valid(q, j, p)) continue;
        if (distance(p, q) < 0.98 * distance(i, j)) {
          // (i, j, p) + (j, i, q) -> (p, i, q) + (q, j, p)
          triangles[f] = {p, i, q};
          triangles[g] = {q, j, p};
          ++flips;
          changed = true;
        }
      }
  }
  return flips;
}

}  // namespace cmaps
