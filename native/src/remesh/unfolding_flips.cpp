#include "remesh/unfolding_flips.h"

#include <array>
#include <cstdint>
#include <optional>
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

// The triangulation with its edges' triangles, for trying flips and taking them back.
class FlipMesh {
 public:
  // Edge a - b of slot f flipped: f and g (b - a's) become (a, d, c) and (d, b, c).
  struct Flip {
    int f, g;
    Triangle old_f, old_g, new_f, new_g;
    int gain;  // folds (triangle, geometry) removed; negative: added
  };

  FlipMesh(std::vector<Triangle>& triangles, const std::vector<char>& flippable,
           const std::vector<FoldGeometry>& geometries)
      : triangles_(triangles), flippable_(flippable), geometries_(geometries) {
    for (int f = 0; f < int(triangles.size()); ++f) link(f);
  }

  // Flipping slot f's edge k, when allowed: both triangles flippable, the
  // quad's other diagonal not an edge yet (so the surface stays manifold).
  std::optional<Flip> candidate(int f, int k) const {
    const Triangle& t = triangles_[f];
    const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
    const std::array<int, 2>& two = faces_.at(edge_key(a, b));
    const int g = two[0] == f ? two[1] : two[0];
    if (g < 0 || !flippable_[f] || !flippable_[g]) return std::nullopt;
    const Triangle& u = triangles_[g];
    const int d = u[0] != a && u[0] != b ? u[0] : u[1] != a && u[1] != b ? u[1] : u[2];
    if (c == d || faces_.count(edge_key(c, d))) return std::nullopt;
    Flip flip{f, g, t, u, {a, d, c}, {d, b, c}, 0};
    flip.gain = fold_count(geometries_, t) + fold_count(geometries_, u) - fold_count(geometries_, flip.new_f) -
                fold_count(geometries_, flip.new_g);
    return flip;
  }

  void apply(const Flip& flip) { replace(flip.f, flip.g, flip.new_f, flip.new_g); }
  void undo(const Flip& flip) { replace(flip.f, flip.g, flip.old_f, flip.old_g); }

 private:
  void link(int f) {
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = faces_.try_emplace(edge_key(triangles_[f][k], triangles_[f][(k + 1) % 3]),
                                            std::array<int, 2>{f, -1});
      if (!added) (it->second[0] < 0 ? it->second[0] : it->second[1]) = f;
    }
  }
  void unlink(int f) {
    for (int k = 0; k < 3; ++k) {
      const auto it = faces_.find(edge_key(triangles_[f][k], triangles_[f][(k + 1) % 3]));
      (it->second[0] == f ? it->second[0] : it->second[1]) = -1;
      if (it->second[0] < 0 && it->second[1] < 0) faces_.erase(it);
    }
  }
  void replace(int f, int g, const Triangle& at_f, const Triangle& at_g) {
    unlink(f), unlink(g);
    triangles_[f] = at_f, triangles_[g] = at_g;
    link(f), link(g);
  }

  std::vector<Triangle>& triangles_;
  const std::vector<char>& flippable_;
  const std::vector<FoldGeometry>& geometries_;
  std::unordered_map<std::uint64_t, std::array<int, 2>> faces_;  // edge -> its triangles (-1: none)
};

}  // namespace

bool folds(const FoldGeometry& geometry, const Triangle& t) {
  const std::vector<Vec3>& x = geometry.positions;
  const Vec3 reference = geometry.normals[t[0]] + geometry.normals[t[1]] + geometry.normals[t[2]];
  return (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).dot(reference) <= 0;
}

int unfold_by_flips(std::vector<Triangle>& triangles, const std::vector<char>& flippable,
                    const std::vector<FoldGeometry>& geometries) {
  FlipMesh mesh(triangles, flippable, geometries);
  int flips = 0;
  for (bool flipped = true; flipped;) {
    flipped = false;
    for (int f = 0; f < int(triangles.size()); ++f) {
      if (!flippable[f] || fold_count(geometries, triangles[f]) == 0) continue;
      // One flip that folds less; else one that folds as much, followed by
      // one of the new triangles' that folds less (a fold walked onto
      // another, the two then gone), or none (undone).
      std::optional<FlipMesh::Flip> first;
      for (int k = 0; k < 3 && !first; ++k)
        if (const auto flip = mesh.candidate(f, k); flip && flip->gain > 0) first = flip;
      if (first) {
        mesh.apply(*first);
        ++flips, flipped = true;
        continue;
      }
      bool paired = false;
      for (int k = 0; k < 3 && !paired; ++k) {
        const auto neutral = mesh.candidate(f, k);
        if (!neutral || neutral->gain < 0) continue;
        mesh.apply(*neutral);
        for (int slot : {neutral->f, neutral->g})
          for (int j = 0; j < 3 && !paired; ++j)
            if (const auto next = mesh.candidate(slot, j); next && next->gain > 0) {
              mesh.apply(*next);
              paired = true;
            }
        if (!paired) mesh.undo(*neutral);
      }
      if (paired) flips += 2, flipped = true;
    }
  }
  return flips;
}

}  // namespace cmaps
