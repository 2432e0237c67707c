#include "remesh/unfolding_flips.h"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <utility>

namespace cmaps {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

int fold_count(const std::vector<FoldGeometry>& geometries, const Triangle& t) {
  int count = 0;
  for (const FoldGeometry& g : geometries) count += folds(g, t);
  return count;
}

}  // namespace

bool folds(const FoldGeometry& geometry, const Triangle& t) {
  const std::vector<Vec3>& x = geometry.positions;
  const Vec3 reference = geometry.normals[t[0]] + geometry.normals[t[1]] + geometry.normals[t[2]];
  return (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).dot(reference) <= 0;
}

int unfold_by_flips(std::vector<Triangle>& triangles, const std::vector<char>& flippable,
                    const std::vector<FoldGeometry>& geometries) {
  // Edge -> its two triangles (-1: none yet).
  std::unordered_map<std::uint64_t, std::array<int, 2>> faces;
  const auto link = [&](int a, int b, int f) {
    auto [it, added] = faces.try_emplace(edge_key(a, b), std::array<int, 2>{f, -1});
    if (!added) it->second[1] = f;
  };
  const auto relink = [&](int a, int b, int from, int to) {
    std::array<int, 2>& two = faces.at(edge_key(a, b));
    (two[0] == from ? two[0] : two[1]) = to;
  };
  for (int f = 0; f < int(triangles.size()); ++f)
    for (int k = 0; k < 3; ++k) link(triangles[f][k], triangles[f][(k + 1) % 3], f);

  int flips = 0;
  for (bool flipped = true; flipped;) {
    flipped = false;
    for (int f = 0; f < int(triangles.size()); ++f) {
      if (!flippable[f] || fold_count(geometries, triangles[f]) == 0) continue;
      for (int k = 0; k < 3; ++k) {
        const Triangle t = triangles[f];
        const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
        const std::array<int, 2>& two = faces.at(edge_key(a, b));
        const int g = two[0] == f ? two[1] : two[0];
        if (g < 0 || !flippable[g]) continue;
        const Triangle& u = triangles[g];
        const int d = u[0] != a && u[0] != b ? u[0] : u[1] != a && u[1] != b ? u[1] : u[2];
        if (c == d || faces.count(edge_key(c, d))) continue;
        // The quad a, d, b, c split along c - d instead of a - b.
        const Triangle first{a, d, c}, second{d, b, c};
        if (fold_count(geometries, first) + fold_count(geometries, second) >=
            fold_count(geometries, t) + fold_count(geometries, u))
          continue;
        faces.erase(edge_key(a, b));
        faces[edge_key(c, d)] = {f, g};
        relink(a, d, g, f);
        relink(b, c, f, g);
        triangles[f] = first, triangles[g] = second;
        ++flips;
        flipped = true;
        if (fold_count(geometries, first) == 0) break;
      }
    }
  }
  return flips;
}

}  // namespace cmaps
