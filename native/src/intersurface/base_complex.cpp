#include "intersurface/base_complex.h"

#include <limits>

#include "consistent_maps/errors.h"
#include "intersurface/chord_energy.h"

namespace cmaps {
namespace {

std::complex<double> complex_of(const Vec2& p) { return {p.x(), p.y()}; }
Vec2 vec_of(const std::complex<double>& z) { return {z.real(), z.imag()}; }

// Side k of base triangle t in its plane: where its path starts and ends.
std::pair<Vec2, Vec2> path_ends(const BaseTriangle& t, int k) {
  const Vec2 &from = kCanonicalCorner[k], &to = kCanonicalCorner[(k + 1) % 3];
  return t.reversed[k] ? std::pair{to, from} : std::pair{from, to};
}

// Whether p lies in the canonical triangle, up to `slack` in barycentric weight.
bool in_canonical_triangle(const Vec2& p, double slack = 0) {
  const auto w = barycentric(p, kCanonicalCorner[0], kCanonicalCorner[1], kCanonicalCorner[2]);
  return w[0] >= -slack && w[1] >= -slack && w[2] >= -slack;
}

// The candidate nearest `near` among those offered.
struct NearestCopy {
  const Vec2& near;
  Vec2& result;
  double best = std::numeric_limits<double>::infinity();
  void consider(const Vec2& q) {
    const double d = (q - near).squaredNorm();
    if (d < best) best = d, result = q;
  }
  bool found() const { return best < std::numeric_limits<double>::infinity(); }
};

}  // namespace

BaseComplex::BaseComplex(const ConsistentPartition& partition, const std::vector<char>& fan)
    : glue_(partition.triangles.size()) {
  for (const BaseTriangle& t : partition.triangles) corners_.push_back(t.corners);
  // Each base edge lies on two sides of base triangles (possibly of one).
  std::vector<std::vector<std::pair<int, int>>> sides(partition.edges.size());
  for (int t = 0; t < int(partition.triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) sides[partition.triangles[t].edges[k]].push_back({t, k});
  for (const auto& pair : sides) {
    if (pair.size() != 2) throw Error("internal error: a base edge does not lie between two base triangle sides");
    for (int i = 0; i < 2; ++i) {
      const auto [t, k] = pair[i];
      const auto [u, j] = pair[1 - i];
      if (fan[t] || fan[u]) continue;
      // The path's ends coincide: a (|a| = 1) and b take u's ends onto t's.
      const auto [t_from, t_to] = path_ends(partition.triangles[t], k);
      const auto [u_from, u_to] = path_ends(partition.triangles[u], j);
      Glue& g = glue_[t][k];
      g.a = (complex_of(t_to) - complex_of(t_from)) / (complex_of(u_to) - complex_of(u_from));
      g.b = complex_of(t_from) - g.a * complex_of(u_from);
      // u must land on the other side of the edge (both embeddings turn alike), else no gluing.
      const Vec2 centre = (kCanonicalCorner[0] + kCanonicalCorner[1] + kCanonicalCorner[2]) / 3;
      const Vec2 &e0 = kCanonicalCorner[k], &e1 = kCanonicalCorner[(k + 1) % 3];
      if (twice_signed_area(e0, e1, from_neighbour(t, k, centre)) * twice_signed_area(e0, e1, centre) >= 0) continue;
      g.neighbour = u;
    }
  }
}

Vec2 BaseComplex::from_neighbour(int t, int k, const Vec2& p) const {
  const Glue& g = glue_[t][k];
  return vec_of(g.a * complex_of(p) + g.b);
}

Vec2 BaseComplex::to_neighbour(int t, int k, const Vec2& p) const {
  const Glue& g = glue_[t][k];
  return vec_of((complex_of(p) - g.b) / g.a);
}

bool BaseComplex::develop(int from, const Vec2& p, int t, const Vec2& near, Vec2& result) const {
  NearestCopy nearest{near, result};
  if (from == t) nearest.consider(p);
  for (int k = 0; k < 3; ++k) {
    const int n = glue_[t][k].neighbour;
    if (n < 0) continue;
    if (n == from) nearest.consider(from_neighbour(t, k, p));
    for (int j = 0; j < 3; ++j)
      if (glue_[n][j].neighbour == from) nearest.consider(from_neighbour(t, k, from_neighbour(n, j, p)));
  }
  return nearest.found();
}

bool BaseComplex::develop_corner(int vertex, int t, const Vec2& near, Vec2& result) const {
  NearestCopy nearest{near, result};
  for (int k = 0; k < 3; ++k) {
    if (corners_[t][k] == vertex) nearest.consider(kCanonicalCorner[k]);
    const int n = glue_[t][k].neighbour;
    if (n < 0) continue;
    for (int j = 0; j < 3; ++j)
      if (corners_[n][j] == vertex) nearest.consider(from_neighbour(t, k, kCanonicalCorner[j]));
  }
  return nearest.found();
}

bool BaseComplex::home_of(int t, const Vec2& p, int& home, Vec2& at) const {
  if (in_canonical_triangle(p, 1e-12)) {
    home = t, at = p;
    return true;
  }
  for (int k = 0; k < 3; ++k) {
    if (glue_[t][k].neighbour < 0) continue;
    const Vec2 q = to_neighbour(t, k, p);
    if (in_canonical_triangle(q)) {
      home = glue_[t][k].neighbour, at = q;
      return true;
    }
  }
  return false;
}

}  // namespace cmaps
