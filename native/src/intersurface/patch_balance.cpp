#include "intersurface/patch_balance.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_set>

#include "common/diagonally_dominant_lu.h"
#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

constexpr double kTolerance = 0.5;    // two patches whose area ratios differ by less than this factor - 1 stay
constexpr double kEdgeClamp = 0.1;    // a new path vertex lies no nearer an edge's ends than this fraction
// Levels stay this far from 0 and 1: where one patch's far sides leave most
// of the two patches near one value, lower levels give paths that hug the
// other sides (kitten - rocker arm medians 16 / 14 -> 51 / 73 with 1e-12).
constexpr double kLevelMargin = 1e-3;
constexpr int kBisections = 40;
// A new path stays at least this fraction of a typical input triangle's size
// (and of its distance to its nearer end, so two paths leaving one base
// vertex keep an angle) from the other paths: where a level curve hugs a
// patch's other side, the patch is pinched into slivers that its embedding
// blows up into canonical area mapping to next to nothing (feline - skull).
constexpr double kPinch = 0.01;
constexpr double kShortestPart = 0.2;  // a path goes all, half or a quarter of the way to its patches' balance

double triangle_area(const PartitionSide& side, int f) {
  const Triangle& t = side.mesh.triangles()[f];
  if (side.in_fan(f)) return 0;
  const Vec3 &a = side.mesh.position(t[0]), &b = side.mesh.position(t[1]), &c = side.mesh.position(t[2]);
  return 0.5 * (b - a).cross(c - a).norm();
}

// Per patch: its share of the side's area.
std::vector<double> area_shares(const PartitionSide& side, int patches) {
  std::vector<double> area(patches, 0);
  double total = 0;
  for (int f = 0; f < int(side.patch.size()); ++f) {
    const double a = triangle_area(side, f);
    area[side.patch[f]] += a, total += a;
  }
  for (double& a : area) a /= total;
  return area;
}

// The largest ratio of a patch's shares between the sides (a hole's fan has none).
double worst_ratio(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 1;
  for (std::size_t t = 0; t < a.size(); ++t)
    if (a[t] > 0 && b[t] > 0) worst = std::max({worst, a[t] / b[t], b[t] / a[t]});
  return worst;
}

// The share of a triangle where a linear function with corner values d is negative.
double share_below(const double d[3]) {
  int negative = 0;
  for (int k = 0; k < 3; ++k) negative += d[k] < 0;
  if (negative == 0) return 0;
  if (negative == 3) return 1;
  // The corner alone on its side cuts off a similar triangle.
  const bool below = negative == 1;
  int k = 0;
  while ((d[k] < 0) != below) ++k;
  const double a = d[k], b = d[(k + 1) % 3], c = d[(k + 2) % 3];
  if (a == 0) return 1;
  const double alone = a * a / ((a - b) * (a - c));
  return below ? alone : 1 - alone;
}

// The two patches beside one path, and the harmonic function over them: on
// their interior vertices (the old path's too) phi = phi0 + t psi, where t is
// the value at the path's ends; the other paths' vertices are 0 in the first
// patch's triangles and 1 in the second's (a base vertex that is a corner of
// both is 0 or 1 by the triangle it is seen from).
class PathRetrace {
 public:
  // `scale`: the side's typical input triangle size (see kPinch).
  PathRetrace(PartitionSide& side, int edge, int first, int second, double scale)
      : side_(side), edge_(edge), first_(first), second_(second), scale_(scale) {
    const auto& path = side.paths[edge];
    ends_ = {path.front(), path.back()};
    std::vector<char> boundary(side.mesh.vertex_count(), 0);
    for (int e = 0; e < int(side.paths.size()); ++e)
      if (e != edge)
        for (int v : side.paths[e]) boundary[v] = 1;
    unknown_.assign(side.mesh.vertex_count(), -1);
    std::unordered_set<int> wall;
    for (int f = 0; f < int(side.patch.size()); ++f)
      if (side.patch[f] == first || side.patch[f] == second) {
        faces_.push_back(f);
        areas_.push_back(triangle_area(side, f));
        for (int v : side.mesh.triangles()[f])
          if (!boundary[v] && !is_end(v) && unknown_[v] < 0) unknown_[v] = unknowns_++;
          else if (boundary[v] && !is_end(v)) wall.insert(v);
      }
    for (int v : wall) walls_.push_back(side.mesh.position(v));
    std::sort(walls_.begin(), walls_.end(), [](const Vec3& p, const Vec3& q) { return p.x() < q.x(); });
    solve();
    for (int f : faces_)
      for (int v : side.mesh.triangles()[f]) corners_.push_back(linear(f, v));
  }

  // The level t at which the first patch takes `share` of the two patches' area.
  double level_for(double share) const {
    double low = kLevelMargin, high = 1 - kLevelMargin;
    for (int i = 0; i < kBisections; ++i) {
      const double t = 0.5 * (low + high);
      (below(t) < share ? low : high) = t;
    }
    return 0.5 * (low + high);
  }

  // Lays the path along the level-t curve; false (nothing changed) when the
  // curve does not run from one end to the other.
  bool retrace(double t) {
    std::vector<Crossing> crossings;
    if (unknowns_ == 0 || !trace(t, crossings) || pinches(crossings)) return false;
    const int triangles_before = int(side_.mesh.triangles().size());
    std::unordered_set<int> level{ends_[0], ends_[1]};
    std::vector<int> path{ends_[0]};
    for (const Crossing& c : crossings) {
      const int e = side_.mesh.edge(c.below, c.above);
      const auto faces = side_.mesh.edge_faces(e);
      const double at = side_.mesh.edge_vertices(e)[0] == c.below ? c.at : 1 - c.at;
      const int m = side_.mesh.split_edge(e, at);
      side_.patch.push_back(side_.patch[faces[0]]);
      side_.patch.push_back(side_.patch[faces[1]]);
      level.insert(m);
      path.push_back(m);
    }
    path.push_back(ends_[1]);
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
      if (side_.mesh.edge(path[i], path[i + 1]) < 0) throw Error("internal error: a re-traced path is not connected");
    side_.paths[edge_] = path;

    // Every triangle of the two patches now lies on one side of the path:
    // below the level is the first patch. Triangles with only level corners
    // take a neighbour's side across an edge off the path.
    for (int f = triangles_before; f < int(side_.mesh.triangles().size()); ++f) faces_.push_back(f);
    std::vector<int> undecided;
    for (int f : faces_) {
      int side = -1;
      for (int v : side_.mesh.triangles()[f])
        if (!level.count(v)) side = value(f, v, t) < t ? first_ : second_;
      if (side >= 0) side_.patch[f] = side;
      else undecided.push_back(f);
    }
    std::unordered_set<int> path_edges;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) path_edges.insert(side_.mesh.edge(path[i], path[i + 1]));
    for (int f : undecided) {
      const Triangle& tri = side_.mesh.triangles()[f];
      for (int k = 0; k < 3; ++k) {
        const int e = side_.mesh.edge(tri[k], tri[(k + 1) % 3]);
        if (path_edges.count(e)) continue;
        const auto faces = side_.mesh.edge_faces(e);
        side_.patch[f] = side_.patch[faces[0] == f ? faces[1] : faces[0]];
        break;
      }
    }
    return true;
  }

 private:
  struct Crossing {
    int below, above;
    double at;  // from `below` towards `above`, kEdgeClamp away from both
  };

  bool is_end(int v) const { return v == ends_[0] || v == ends_[1]; }
  int unknown(int v) const { return v < int(unknown_.size()) ? unknown_[v] : -1; }

  // Whether a path through the crossings would come too near another path (kPinch).
  bool pinches(const std::vector<Crossing>& crossings) const {
    const EditableMesh& mesh = side_.mesh;
    for (const Crossing& c : crossings) {
      const Vec3 x = (1 - c.at) * mesh.position(c.below) + c.at * mesh.position(c.above);
      const double end = std::min((x - mesh.position(ends_[0])).norm(), (x - mesh.position(ends_[1])).norm());
      const double limit = kPinch * std::min(scale_, end);
      // Only walls within the limit in x can be within it.
      auto w = std::lower_bound(walls_.begin(), walls_.end(), x.x() - limit,
                                [](const Vec3& p, double low) { return p.x() < low; });
      for (; w != walls_.end() && w->x() <= x.x() + limit; ++w)
        if ((x - *w).squaredNorm() < limit * limit) return true;
    }
    return false;
  }

  // The function at corner v of triangle f, as {a, b}: a + t b at level t.
  std::array<double, 2> linear(int f, int v) const {
    if (is_end(v)) return {0, 1};
    const int i = unknown(v);
    if (i >= 0) return {phi0_[i], psi_[i]};
    return {side_.patch[f] == first_ ? 0.0 : 1.0, 0};
  }

  double value(int f, int v, double t) const {
    const auto [a, b] = linear(f, v);
    return a + t * b;
  }

  // Mean-value weights, assembled triangle by triangle, so that a boundary
  // vertex takes its value from the triangle that sees it.
  void solve() {
    const int n = unknowns_;
    if (n == 0) return;
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd rhs0 = Eigen::VectorXd::Zero(n), rhs_psi = Eigen::VectorXd::Zero(n);
    for (int f : faces_) {
      const Triangle& t = side_.mesh.triangles()[f];
      for (int k = 0; k < 3; ++k) {
        const int i = unknown(t[k]);
        if (i < 0) continue;
        const Vec3& p = side_.mesh.position(t[k]);
        const Vec3 u = side_.mesh.position(t[(k + 1) % 3]) - p, w = side_.mesh.position(t[(k + 2) % 3]) - p;
        const double half = std::tan(0.5 * std::atan2(u.cross(w).norm(), u.dot(w)));
        for (const auto& [v, d] : {std::pair<int, Vec3>{t[(k + 1) % 3], u}, {t[(k + 2) % 3], w}}) {
          const double weight = half / std::max(d.norm(), 1e-300);
          entries.emplace_back(i, i, weight);
          const int j = unknown(v);
          if (j >= 0) entries.emplace_back(i, j, -weight);
          else if (is_end(v)) rhs_psi[i] += weight;
          else rhs0[i] += weight * (side_.patch[f] == first_ ? 0 : 1);
        }
      }
    }
    Eigen::SparseMatrix<double> matrix(n, n);
    matrix.setFromTriplets(entries.begin(), entries.end());
    DiagonallyDominantLU lu;
    lu.compute(matrix);
    if (lu.info() != Eigen::Success) throw Error("internal error: the path's harmonic function has no solution");
    phi0_ = lu.solve(rhs0);
    psi_ = lu.solve(rhs_psi);
  }

  // The share of the two patches' area below level t.
  double below(double t) const {
    double under = 0, total = 0;
    for (std::size_t i = 0; i < areas_.size(); ++i) {
      double d[3];
      for (int k = 0; k < 3; ++k) d[k] = corners_[3 * i + k][0] + t * corners_[3 * i + k][1] - t;
      under += areas_[i] * share_below(d), total += areas_[i];
    }
    return under / total;
  }

  // The level-t curve from the first end, triangle by triangle, to the second.
  bool trace(double t, std::vector<Crossing>& crossings) const {
    std::unordered_set<int> quad(faces_.begin(), faces_.end());
    const auto is_below = [&](int f, int v) { return value(f, v, t) < t; };
    const auto crossing = [&](int f, int x, int y) {
      const double dx = value(f, x, t) - t, dy = value(f, y, t) - t;
      return Crossing{x, y, std::clamp(dx / (dx - dy), kEdgeClamp, 1 - kEdgeClamp)};
    };
    for (int start : side_.mesh.faces_of(ends_[0])) {
      if (!quad.count(start)) continue;
      const Triangle& s = side_.mesh.triangles()[start];
      int k = 0;
      while (s[k] != ends_[0]) ++k;
      int x = s[(k + 1) % 3], y = s[(k + 2) % 3];
      if (is_end(x) || is_end(y) || is_below(start, x) == is_below(start, y)) continue;
      if (!is_below(start, x)) std::swap(x, y);
      crossings = {crossing(start, x, y)};
      int from = start;
      for (std::size_t step = 0; step <= faces_.size(); ++step) {
        const auto faces = side_.mesh.edge_faces(side_.mesh.edge(x, y));
        const int next = faces[0] == from ? faces[1] : faces[0];
        if (!quad.count(next)) break;
        const Triangle& tri = side_.mesh.triangles()[next];
        int z = tri[0];
        for (int v : tri)
          if (v != x && v != y) z = v;
        if (z == ends_[1]) return true;
        if (z == ends_[0]) break;
        (is_below(next, z) ? x : y) = z;
        crossings.push_back(crossing(next, x, y));
        from = next;
      }
    }
    return false;
  }

  PartitionSide& side_;
  int edge_, first_, second_;
  std::array<int, 2> ends_{};
  std::vector<int> faces_;     // the two patches' triangles (after a retrace, the new ones too)
  std::vector<double> areas_;  // per triangle of faces_ before the retrace
  // Per corner of those triangles, the function as linear() gives it: the
  // bisections of level_for read it for every triangle some 40 times.
  std::vector<std::array<double, 2>> corners_;
  // Per mesh vertex (as the retrace found the mesh), its unknown: the two
  // patches' interior vertices, the old path's too; -1 for the others.
  std::vector<int> unknown_;
  int unknowns_ = 0;
  double scale_;                           // the side's typical input triangle size
  std::vector<Vec3> walls_;                // the two patches' other sides (no ends), by x
  Eigen::VectorXd phi0_, psi_;
};

}  // namespace

double patch_area_ratio(const ConsistentPartition& partition) {
  const int patches = int(partition.triangles.size());
  return worst_ratio(area_shares(partition.sides[0], patches), area_shares(partition.sides[1], patches));
}

PatchBalance balance_patch_areas(ConsistentPartition& partition, int rounds) {
  const int patches = int(partition.triangles.size());
  std::vector<std::array<int, 2>> beside(partition.edges.size(), {-1, -1});
  for (int t = 0; t < patches; ++t)
    for (int e : partition.triangles[t].edges) (beside[e][0] < 0 ? beside[e][0] : beside[e][1]) = t;
  // A hole's fan stays a fan, and its rim its rim.
  std::vector<char> in_hole(patches, 0);
  const PartitionSide& a = partition.sides[0];
  for (int f = 0; f < int(a.patch.size()); ++f)
    if (a.in_fan(f)) in_hole[a.patch[f]] = 1;
  const auto shares_another_path = [&](int p, int q, int edge) {
    for (int e : partition.triangles[p].edges)
      if (e != edge && (beside[e][0] == q || beside[e][1] == q)) return true;
    return false;
  };

  std::array<double, 2> scale;
  for (int s = 0; s < 2; ++s) {
    double area = 0;
    for (int f = 0; f < int(partition.sides[s].patch.size()); ++f) area += triangle_area(partition.sides[s], f);
    scale[s] = std::sqrt(area / partition.sides[s].input_triangles);
  }
  PatchBalance result;
  std::array<std::vector<double>, 2> own = {area_shares(partition.sides[0], patches),
                                            area_shares(partition.sides[1], patches)};
  result.worst_before = worst_ratio(own[0], own[1]);
  for (int round = 0; round < rounds; ++round) {
    int moved = 0;
    for (int e = 0; e < int(partition.edges.size()); ++e) {
      const auto [p, q] = beside[e];
      if (p < 0 || q < 0 || p == q || in_hole[p] || in_hole[q] || shares_another_path(p, q, e)) continue;
      const double ra = own[0][p] / own[0][q], rb = own[1][p] / own[1][q];
      if (std::abs(std::log(ra / rb)) < std::log1p(kTolerance)) continue;
      // Both sides meet halfway (moving one side alone is worse on every pair
      // measured), or, where that path would pinch a patch, go part of the way.
      const double target = std::sqrt(ra * rb);
      for (int s = 0; s < 2; ++s) {
        PathRetrace retrace(partition.sides[s], e, p, q, scale[s]);
        const double now = s == 0 ? ra : rb;
        for (double part = 1; part > kShortestPart; part /= 2) {
          const double ratio = std::pow(now, 1 - part) * std::pow(target, part);
          if (!retrace.retrace(retrace.level_for(ratio / (1 + ratio)))) continue;
          ++moved;
          own[s] = area_shares(partition.sides[s], patches);
          break;
        }
      }
    }
    result.retraced += moved;
    if (moved == 0) break;
  }
  result.worst_after = worst_ratio(own[0], own[1]);
  return result;
}

}  // namespace cmaps
