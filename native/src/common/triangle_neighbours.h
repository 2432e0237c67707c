// The triangle across each edge of each triangle: shared by the texture charts
// of the attribute transfer (stepping across seams) and the spherical map
// optimizer's region moves (walking to the triangle that holds a point).
#pragma once
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// Per triangle, per edge k (corner k to corner k + 1): the other triangle
// sharing that edge, or -1 on a boundary. Where more than two triangles share
// an edge, the first two seen are paired.
inline std::vector<std::array<int, 3>> triangle_neighbours(const std::vector<Triangle>& triangles) {
  std::vector<std::array<int, 3>> neighbours(triangles.size(), {-1, -1, -1});
  std::unordered_map<std::uint64_t, int> first;  // undirected edge -> first triangle seen
  const auto key = [](int p, int q) {
    return (std::uint64_t(std::uint32_t(std::min(p, q))) << 32) | std::uint32_t(std::max(p, q));
  };
  for (int t = 0; t < int(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto [it, added] = first.emplace(key(triangles[t][k], triangles[t][(k + 1) % 3]), t);
      if (added || it->second == t) continue;
      neighbours[t][k] = it->second;
      const int other = it->second;
      for (int j = 0; j < 3; ++j)
        if (neighbours[other][j] < 0 && key(triangles[other][j], triangles[other][(j + 1) % 3]) == it->first)
          neighbours[other][j] = t;
    }
  return neighbours;
}

}  // namespace cmaps
