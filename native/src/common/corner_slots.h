// Where a triangle's corners sit in a sorted list of vertices: a move that
// carries some vertices along looks them up once, not in every trial.
#pragma once
#include <algorithm>
#include <array>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// Per corner of t: its index in `sorted` (ascending by `vertex_of` of each
// entry), -1 if not there.
template <class Entry, class VertexOf>
std::array<int, 3> corner_slots(const Triangle& t, const std::vector<Entry>& sorted, const VertexOf& vertex_of) {
  std::array<int, 3> slots;
  for (int k = 0; k < 3; ++k) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), t[k],
                                     [&](const Entry& e, int v) { return vertex_of(e) < v; });
    slots[k] = it != sorted.end() && vertex_of(*it) == t[k] ? int(it - sorted.begin()) : -1;
  }
  return slots;
}

// The same for a sorted list of vertex indices.
inline std::array<int, 3> corner_slots(const Triangle& t, const std::vector<int>& sorted) {
  return corner_slots(t, sorted, [](int v) { return v; });
}

}  // namespace cmaps
