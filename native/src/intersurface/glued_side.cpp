#include "intersurface/glued_side.h"

#include <algorithm>

#include "intersurface/chord_energy.h"

namespace cmaps {
namespace {

const Vec2 kCentre = (kCanonicalCorner[0] + kCanonicalCorner[1] + kCanonicalCorner[2]) / 3;

// Whether the 2D triangle c overlaps the canonical triangle (more than
// touching it): no side of either separates them.
bool overlaps_canonical(const std::array<Vec2, 3>& c) {
  const std::array<Vec2, 3> canonical = {kCanonicalCorner[0], kCanonicalCorner[1], kCanonicalCorner[2]};
  const auto separates = [](const std::array<Vec2, 3>& p, const std::array<Vec2, 3>& q) {
    const double turn = twice_signed_area(p[0], p[1], p[2]) >= 0 ? 1 : -1;
    for (int k = 0; k < 3; ++k) {
      const Vec2 &from = p[k], &to = p[(k + 1) % 3];
      if (std::all_of(q.begin(), q.end(), [&](const Vec2& x) { return turn * twice_signed_area(from, to, x) <= 0; }))
        return true;
    }
    return false;
  };
  return !separates(c, canonical) && !separates(canonical, c);
}

}  // namespace

GluedEmbedding glue_patches(const PartitionSide& side, const PatchParameterization& uv) {
  const int n = side.mesh.vertex_count();
  GluedEmbedding glued{std::vector<int>(n, -1), std::vector<Vec2>(n, Vec2::Zero()), {}};
  glued.fan_uv.resize(uv.uv.size());
  for (int f = 0; f < int(side.patch.size()); ++f)
    if (side.in_fan(f) && glued.fan_uv[side.patch[f]].empty()) glued.fan_uv[side.patch[f]] = uv.uv[side.patch[f]];
  for (int v = 0; v < n; ++v) {
    const std::vector<int>& faces = side.mesh.faces_of(v);
    const auto surface = std::find_if(faces.begin(), faces.end(), [&](int f) { return !side.in_fan(f); });
    glued.home[v] = side.patch[surface != faces.end() ? *surface : faces.front()];
    glued.point[v] = uv.uv[glued.home[v]].at(v);
  }
  return glued;
}

GluedSide::GluedSide(const PartitionSide& side, const BaseComplex& base, GluedEmbedding embedding)
    : side_(side), base_(base), embedding_(std::move(embedding)), base_vertex_(side.mesh.vertex_count(), -1) {
  for (int k = 0; k < int(side.feature_vertex.size()); ++k) base_vertex_[side.feature_vertex[k]] = k;
}

bool GluedSide::develop(int u, int t, const Vec2& near, Vec2& result) const {
  if (!embedding_.fan_uv[t].empty()) {
    const auto it = embedding_.fan_uv[t].find(u);
    if (it != embedding_.fan_uv[t].end()) result = it->second;
    return it != embedding_.fan_uv[t].end();
  }
  return base_vertex_[u] >= 0 ? base_.develop_corner(base_vertex_[u], t, near, result)
                              : base_.develop(home(u), point(u), t, near, result);
}

int GluedSide::develop_triangle(int f, const std::array<double, 3>& weights, std::array<Vec2, 3>& corners) const {
  const Triangle& t = side_.mesh.triangles()[f];
  int anchor = -1;
  for (int k = 0; k < 3; ++k)
    if (base_vertex_[t[k]] < 0 && (anchor < 0 || weights[k] > weights[anchor])) anchor = k;
  const int plane = anchor < 0 ? side_.patch[f] : home(t[anchor]);
  const Vec2 near = anchor < 0 ? kCentre : point(t[anchor]);
  for (int k = 0; k < 3; ++k)
    if (!develop(t[k], plane, near, corners[k])) return -1;
  return plane;
}

bool GluedSide::canonical_point(int f, const std::array<double, 3>& weights, int& home, Vec2& point) const {
  std::array<Vec2, 3> c;
  const int plane = develop_triangle(f, weights, c);
  if (plane < 0) return false;
  const Vec2 p = weights[0] * c[0] + weights[1] * c[1] + weights[2] * c[2];
  return base_.home_of(plane, p, home, point);
}

std::vector<PatchLocator> GluedSide::locators() const {
  const int patches = base_.triangles();
  std::vector<std::vector<int>> faces(patches);
  std::vector<std::vector<std::array<Vec2, 3>>> corners(patches);
  const auto add = [&](int f, int t, const std::array<Vec2, 3>& c) {
    if (!faces[t].empty() && faces[t].back() == f) return;
    if (!overlaps_canonical(c)) return;
    faces[t].push_back(f);
    corners[t].push_back(c);
  };
  for (int f = 0; f < int(side_.mesh.triangles().size()); ++f) {
    const Triangle& tri = side_.mesh.triangles()[f];
    std::array<Vec2, 3> c;
    if (side_.in_fan(f)) {  // laid out in its fan alone
      const int t = side_.patch[f];
      if (develop(tri[0], t, kCentre, c[0]) && develop(tri[1], t, kCentre, c[1]) && develop(tri[2], t, kCentre, c[2]))
        add(f, t, c);
      continue;
    }
    // In the plane of each corner's home (exact for that corner, the others
    // nearest it), and carried across each side of that plane: a triangle
    // reaches no farther (a base triangle beside another across two sides
    // gets the copy across each; only the right one overlaps it).
    std::vector<std::pair<int, Vec2>> planes;  // with the point the corners develop near
    for (int v : tri)
      if (base_vertex_[v] < 0) planes.push_back({home(v), point(v)});
    if (planes.empty()) planes.push_back({side_.patch[f], kCentre});
    for (const auto& [plane, near] : planes) {
      bool developed = true;
      for (int j = 0; j < 3; ++j) developed = developed && develop(tri[j], plane, near, c[j]);
      if (!developed) continue;
      add(f, plane, c);
      for (int side = 0; side < 3; ++side) {
        const int t = base_.neighbour(plane, side);
        if (t < 0) continue;
        std::array<Vec2, 3> across;
        for (int j = 0; j < 3; ++j) across[j] = base_.to_neighbour(plane, side, c[j]);
        add(f, t, across);
      }
    }
  }
  std::vector<PatchLocator> result;
  result.reserve(patches);
  for (int t = 0; t < patches; ++t) result.emplace_back(std::move(faces[t]), std::move(corners[t]));
  return result;
}

}  // namespace cmaps
