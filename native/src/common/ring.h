// The one-ring of a vertex in counter-clockwise order, from its triangles.
#pragma once
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// `star` holds the triangles around v, each containing v once and oriented
// counter-clockwise; each contributes the ring edge that follows v in it.
// Returns the neighbours in that order, starting anywhere.
inline std::vector<int> ring_around(int v, const std::vector<Triangle>& star) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(star.size());
  for (const Triangle& t : star) {
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    edges.emplace_back(t[(k + 1) % 3], t[(k + 2) % 3]);
  }
  std::vector<int> ring;
  ring.reserve(edges.size());
  int current = edges.front().first;
  for (size_t i = 0; i < edges.size(); ++i) {
    ring.push_back(current);
    for (const auto& [from, to] : edges)
      if (from == current) {
        current = to;
        break;
      }
  }
  return ring;
}

}  // namespace cmaps
