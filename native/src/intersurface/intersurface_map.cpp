// Inter-surface maps (issue 5): genus 0 by the composition of two consistent
// spherical parameterizations, genus >= 1 through a consistent partition
// into patches. See intersurface_map.h.
#include "consistent_maps/intersurface_map.h"

#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>

#include "common/parallel_for.h"
#include "common/side_by_side.h"
#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/sphere_locator.h"
#include "consistent/parameterize_with_reference.h"
#include "consistent_maps/stretch_metric.h"
#include "intersurface/sphere_map_optimizer.h"
#include "intersurface/sphere_pair.h"
#include "intersurface/symmetric_dirichlet.h"
#include "intersurface/consistent_partition.h"
#include "intersurface/patch_balance.h"
#include "intersurface/patch_map_optimization.h"
#include "intersurface/cross_patch_optimization.h"
#include "intersurface/patch_parameterization.h"
#include "intersurface/path_guide.h"
#include "intersurface/hole_rims.h"
#include "paths/mesh_holes.h"

namespace cmaps {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

ProgressCallback slice(const ProgressCallback& progress, double begin, double end) {
  if (!progress) return {};
  return [&progress, begin, end](double f, const std::string& stage) { return progress(begin + (end - begin) * f, stage); };
}

// The genus of one closed, manifold, consistently oriented, connected mesh;
// TopologyError naming the mesh (`name` is "A" or "B") otherwise.
int checked_genus(const TriangleMesh& mesh, const std::string& name) {
  const MeshReport r = check_mesh(mesh);
  const bool usable = r.vertices > 0 && r.genus >= 0 && r.manifold() &&
                      r.components == 1 && r.referenced_vertices == r.vertices &&
                      r.inconsistently_oriented_edges == 0 && r.non_finite_vertices == 0 &&
                      r.out_of_range_indices == 0;
  if (!usable)
    throw TopologyError(name + ": mesh has " + summarize(r) +
                        "; an inter-surface map needs one manifold, consistently oriented surface (closed or with "
                        "separate holes)");
  return r.genus;
}

void check_features(const std::vector<FeaturePair>& features, const TriangleMesh& a, const TriangleMesh& b) {
  std::map<int, std::size_t> seen_a, seen_b;
  for (std::size_t k = 0; k < features.size(); ++k) {
    const std::string pair = "feature pair " + std::to_string(k);
    const auto check = [&](int v, const TriangleMesh& mesh, const char* name, std::map<int, std::size_t>& seen) {
      const int n = int(mesh.vertices.size());
      if (v < 0 || v >= n)
        throw InvalidInput(pair + ": vertex " + std::to_string(v) + " is out of range for " + name + " (" +
                           std::to_string(n) + " vertices)");
      const auto [it, inserted] = seen.emplace(v, k);
      if (!inserted)
        throw InvalidInput("feature pairs " + std::to_string(it->second) + " and " + std::to_string(k) +
                           " both use vertex " + std::to_string(v) + " of " + name);
    };
    check(features[k].a, a, "A", seen_a);
    check(features[k].b, b, "B", seen_b);
  }
}

// Rotation R with R x_i close to y_i (least squares); identity without pairs,
// the shortest rotation for one pair.
Eigen::Matrix3d align(const std::vector<Vec3>& x, const std::vector<Vec3>& y) {
  if (x.empty()) return Eigen::Matrix3d::Identity();
  if (x.size() == 1) return Eigen::Quaterniond::FromTwoVectors(x[0], y[0]).toRotationMatrix();
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) h += x[i] * y[i].transpose();
  if (x.size() == 2) h += x[0].cross(x[1]) * y[0].cross(y[1]).transpose();  // pins the rotation about the pair
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  return svd.matrixV() * d * svd.matrixU().transpose();
}

// Adds pairs until there are `wanted`: see the header. Returns the time spent.
void add_features(const TriangleMesh& a, const TriangleMesh& b, std::vector<FeaturePair>& features,
                  std::size_t wanted, const SphereOptions& options, const ProgressCallback& progress) {
  const SphereResult sa = spherical_parameterization(a, options, slice(progress, 0, 0.5));
  const SphereResult sb = spherical_parameterization(b, options, slice(progress, 0.5, 1));
  std::vector<Vec3> x, y;
  for (const FeaturePair& f : features) x.push_back(sa.sphere[f.a]), y.push_back(sb.sphere[f.b]);
  const Eigen::Matrix3d rotation = align(x, y);
  const SphereLocator locator(sb.sphere, b.triangles);

  std::vector<char> used_a(a.vertices.size(), 0), used_b(b.vertices.size(), 0);
  std::vector<double> distance(a.vertices.size(), std::numeric_limits<double>::infinity());
  std::vector<Vec3> points(a.vertices.size());
  for (std::size_t v = 0; v < points.size(); ++v) points[v] = rotation * sa.sphere[v];
  const auto take = [&](int v) {
    for (std::size_t u = 0; u < points.size(); ++u)
      distance[u] = std::min(distance[u], (points[u] - points[v]).squaredNorm());
  };
  for (const FeaturePair& f : features) used_a[f.a] = used_b[f.b] = 1, take(f.a);
  int candidate = features.empty() ? 0 : -1;
  while (features.size() < wanted) {
    if (candidate < 0) {
      double best = -1;
      for (std::size_t u = 0; u < points.size(); ++u)
        if (!used_a[u] && distance[u] > best) best = distance[u], candidate = int(u);
      if (candidate < 0) throw InvalidInput("A has too few vertices for " + std::to_string(wanted) + " features");
    }
    const SphereLocation at = locator.locate(points[candidate]);
    const auto& corners = b.triangles[at.triangle];
    const int k = int(std::max_element(at.barycentric.begin(), at.barycentric.end()) - at.barycentric.begin());
    used_a[candidate] = 1;
    if (!used_b[corners[k]]) {
      used_b[corners[k]] = 1;
      features.push_back({candidate, corners[k]});
      take(candidate);
    }
    candidate = -1;
  }
}

// Barycentric coordinates of x w.r.t. triangle (p0, p1, p2), projected onto
// its plane, clamped to the triangle and normalized.
std::array<double, 3> project(const Vec3& x, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0, d = x - p0;
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2), det = a * c - b * b;
  std::array<double, 3> w{1.0 / 3, 1.0 / 3, 1.0 / 3};
  if (det > 0) {
    const double s = (c * d.dot(e1) - b * d.dot(e2)) / det, t = (a * d.dot(e2) - b * d.dot(e1)) / det;
    w = {std::max(0.0, 1 - s - t), std::max(0.0, s), std::max(0.0, t)};
  }
  const double sum = w[0] + w[1] + w[2];
  if (sum > 0) for (double& v : w) v /= sum;
  else w = {1, 0, 0};
  return w;
}

// A point of `map`'s refined triangulation (triangle, barycentric) as a point
// of the input triangle it lies in, w.r.t. that triangle's corners.
SurfacePoint to_input(const TriangleMesh& mesh, const ConstrainedResult& map, const SphereLocation& at) {
  const int n = int(mesh.vertices.size());
  SurfacePoint p;
  p.triangle = map.input_triangle[at.triangle];
  const Triangle& corners = mesh.triangles[p.triangle];
  double stray = 0;  // weight on vertices that are not corners (never, up to the refinement's bookkeeping)
  Vec3 x = Vec3::Zero();
  const auto add = [&](int v, double w) {
    x += w * mesh.vertices[v];
    for (int j = 0; j < 3; ++j)
      if (corners[j] == v) {
        p.barycentric[j] += w;
        return;
      }
    stray += std::abs(w);
  };
  const Triangle& refined = map.triangles[at.triangle];
  for (int k = 0; k < 3; ++k) {
    const int c = refined[k];
    const double w = at.barycentric[k];
    if (c < n) {
      add(c, w);
    } else {
      const SteinerVertex& s = map.steiner[c - n];
      for (int j = 0; j < 3; ++j)
        if (s.vertices[j] >= 0) add(s.vertices[j], w * s.weights[j]);
    }
  }
  if (stray > 1e-12) {
    p.barycentric = project(x, mesh.vertices[corners[0]], mesh.vertices[corners[1]], mesh.vertices[corners[2]]);
    return p;
  }
  double sum = 0;
  for (double& w : p.barycentric) sum += (w = std::max(0.0, w));
  for (double& w : p.barycentric) w /= sum;
  return p;
}

}  // namespace

std::vector<SurfacePoint> map_through_sphere(const std::vector<Vec3>& source_sphere, const TriangleMesh& target,
                                             const ConstrainedResult& target_map,
                                             const std::vector<std::pair<int, int>>& exact, int threads) {
  // Holes are closed by their temporary fans so that every direction lands
  // somewhere. Both meshes' boundaries lie on the same great-circle arcs (a
  // chord projects onto its arc), so only directions on a boundary, up to
  // rounding, land in a fan: they move onto its boundary edge, on the real
  // triangle across it.
  const ParameterizedSurface surface = parameterized_surface(target, target_map, /*close_holes=*/true);
  const SphereLocator locator(surface.sphere, surface.surface.triangles);
  std::vector<SphereLocation> located = locator.locate_all(source_sphere, threads);
  if (target_map.holes > 0) {
    const int real = int(target_map.triangles.size()), first_centre = int(surface.sphere.size()) - target_map.holes;
    std::map<std::pair<int, int>, int> beside;  // boundary edge (u, v) of a fan -> the real triangle with edge (v, u)
    for (int f = 0; f < real; ++f)
      for (int k = 0; k < 3; ++k) beside[{target_map.triangles[f][(k + 1) % 3], target_map.triangles[f][k]}] = f;
    for (SphereLocation& at : located) {
      if (at.triangle < real) continue;
      const Triangle& fan = surface.surface.triangles[at.triangle];
      const int k = fan[0] >= first_centre ? 0 : fan[1] >= first_centre ? 1 : 2;
      const int u = fan[(k + 1) % 3], v = fan[(k + 2) % 3];
      double wu = at.barycentric[(k + 1) % 3], wv = at.barycentric[(k + 2) % 3];
      if (!(wu + wv > 0)) wu = wv = 1;
      const auto edge = beside.find({u, v});
      if (edge == beside.end()) throw Error("internal error: a hole's boundary edge has no triangle");
      at.triangle = edge->second;
      const Triangle& t = target_map.triangles[at.triangle];
      for (int j = 0; j < 3; ++j) at.barycentric[j] = t[j] == u ? wu / (wu + wv) : t[j] == v ? wv / (wu + wv) : 0;
    }
  }
  std::vector<SurfacePoint> points(located.size());
  parallel_for(int(located.size()), threads, [&](int i) { points[i] = to_input(target, target_map, located[i]); });

  std::vector<int> incident(target.vertices.size(), -1);  // one triangle per vertex
  for (std::size_t t = 0; t < target.triangles.size(); ++t)
    for (int v : target.triangles[t])
      if (incident[v] < 0) incident[v] = int(t);
  for (const auto& [from, to] : exact) {
    SurfacePoint& p = points[from];
    p.triangle = incident[to];
    for (int j = 0; j < 3; ++j) p.barycentric[j] = target.triangles[p.triangle][j] == to ? 1 : 0;
  }
  return points;
}

// Sphere directions of a point next to every corner of every input triangle
// (3 t + k), moved by kCornerNudge towards the other two corners inside a
// refined triangle of that input triangle incident to the corner (the map is
// linear there); without one (zero-area input triangles), between the input
// corners' own directions.
std::vector<Vec3> corner_directions(const TriangleMesh& mesh, const ConstrainedResult& map) {
  const ParameterizedSurface surface = parameterized_surface(mesh, map);
  const std::vector<Vec3>& sphere = surface.sphere;
  std::vector<Vec3> directions(3 * mesh.triangles.size());
  std::vector<char> found(directions.size(), 0);
  const auto nudged = [](const Vec3& at, const Vec3& b, const Vec3& c) {
    return Vec3((1 - 2 * kCornerNudge) * at + kCornerNudge * (b + c)).normalized();
  };
  for (std::size_t r = 0; r < map.triangles.size(); ++r) {
    const int t = map.input_triangle[r];
    const Triangle& refined = map.triangles[r];
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const std::size_t slot = 3 * std::size_t(t) + std::size_t(k);
        if (found[slot] || refined[j] != mesh.triangles[t][k]) continue;
        directions[slot] = nudged(sphere[refined[j]], sphere[refined[(j + 1) % 3]], sphere[refined[(j + 2) % 3]]);
        found[slot] = 1;
      }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (!found[3 * t + k]) {
        const Triangle& c = mesh.triangles[t];
        directions[3 * t + k] = nudged(map.sphere[c[k]], map.sphere[c[(k + 1) % 3]], map.sphere[c[(k + 2) % 3]]);
      }
  return directions;
}

double composition_dirichlet(const TriangleMesh& a, const ConstrainedResult& map_a, const TriangleMesh& b,
                             const ConstrainedResult& map_b, int threads) {
  return measure_intersurface_map(a, b, map_through_sphere(map_a.sphere, b, map_b, {}, threads)).symmetric_dirichlet +
         measure_intersurface_map(b, a, map_through_sphere(map_b.sphere, a, map_a, {}, threads)).symmetric_dirichlet;
}

namespace {

// Lowers the symmetric distortion of the composed map (see MapOptimizer);
// feature vertices stay on their common points. Holes are closed by their
// fans, whose corners (the rims and the centres) stay put: the rims stay on
// their arcs, and no vertex can enter a hole, since none leaves its star.
void optimize_composition(const TriangleMesh& a, ConstrainedResult& map_a, const TriangleMesh& b,
                          ConstrainedResult& map_b, const std::vector<FeaturePair>& features,
                          const IntersurfaceOptions& options, const ProgressCallback& progress) {
  ParameterizedSurface pa = parameterized_surface(a, map_a, /*close_holes=*/true),
                       pb = parameterized_surface(b, map_b, /*close_holes=*/true);
  std::vector<char> fixed_a(pa.sphere.size(), 0), fixed_b(pb.sphere.size(), 0);
  for (const FeaturePair& f : features) fixed_a[f.a] = fixed_b[f.b] = 1;
  for (const auto& [map, p, fixed] : {std::tuple<const ConstrainedResult&, const ParameterizedSurface&,
                                                 std::vector<char>&>{map_a, pa, fixed_a},
                                      {map_b, pb, fixed_b}})
    for (std::size_t t = map.triangles.size(); t < p.surface.triangles.size(); ++t)
      for (int v : p.surface.triangles[t]) fixed[v] = 1;
  std::vector<int> centres_a, centres_b;
  for (const FeaturePair& f : features) centres_a.push_back(f.a), centres_b.push_back(f.b);
  MapOptimizer optimizer({pa.surface, a.triangles, pa.sphere, fixed_a, centres_a},
                         {pb.surface, b.triangles, pb.sphere, fixed_b, centres_b}, options.sphere.threads);
  bool cancelled = false;
  const auto going_on = [&](double done) {
    cancelled = progress && !progress(done, "optimizing the map");
    return !cancelled;
  };
  optimizer.optimize(options.optimize_rounds, options.optimize_sweeps, 1e-3, options.optimize_regions, going_on);
  if (cancelled) throw Cancelled();
  for (const auto& [p, map] : {std::pair<const ParameterizedSurface&, ConstrainedResult&>{pa, map_a}, {pb, map_b}}) {
    const size_t n = map.sphere.size();
    std::copy(p.sphere.begin(), p.sphere.begin() + n, map.sphere.begin());
    for (size_t i = 0; i < map.steiner.size(); ++i) map.steiner[i].sphere = p.sphere[n + i];
  }
}

// The vertex of `mesh` farthest from `point`.
int farthest_from(const TriangleMesh& mesh, const Vec3& point) {
  int best = 0;
  for (int v = 1; v < int(mesh.vertices.size()); ++v)
    if ((mesh.vertices[v] - point).squaredNorm() > (mesh.vertices[best] - point).squaredNorm()) best = v;
  return best;
}

// The vertex farthest from the centroid: the automatic feature of a mesh.
int farthest_from_centroid(const TriangleMesh& mesh) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) centroid += v;
  return farthest_from(mesh, centroid / double(mesh.vertices.size()));
}

// The automatic feature of restart `start`: the start-th of the vertices
// spread by farthest-point sampling from the one farthest from the centroid.
int spread_vertex(const TriangleMesh& mesh, int start) {
  int chosen = farthest_from_centroid(mesh);
  std::vector<double> distance(mesh.vertices.size(), std::numeric_limits<double>::infinity());
  for (int k = 0; k < start; ++k) {
    for (std::size_t v = 0; v < distance.size(); ++v)
      distance[v] = std::min(distance[v], (mesh.vertices[v] - mesh.vertices[chosen]).squaredNorm());
    chosen = int(std::max_element(distance.begin(), distance.end()) - distance.begin());
  }
  return chosen;
}

// A -> B plus B -> A median distortion.
double summed_median(const IntersurfaceResult& r) {
  return r.distortion_a_to_b.median_symmetric_dirichlet + r.distortion_b_to_a.median_symmetric_dirichlet;
}

// A -> B plus B -> A folded samples.
int summed_folds(const IntersurfaceResult& r) { return r.distortion_a_to_b.flipped + r.distortion_b_to_a.flipped; }

// Whether map x of a pair is better than map y: the lower summed median,
// unless the medians lie within 5 % of each other. Such medians are a tie
// the energy cannot break (restarts of one sphere map differ by 1-2 %; the
// truth of sets/faces is more distorted than both maps): the map that folds
// fewer sampled triangles (both directions) by more than 0.5 % of the
// `samples` (A's triangles plus B's) wins, folds showing as inverted faces
// in a morph; with fold counts closer than that, x when `x_wins_ties`, else
// still the lower median. Fold counts a few apart are noise (on sets/faces
// and the torus against its stretched copy they picked the farther map as
// often as not); hundreds apart they are not: sets/cactus 2 -> 0, 12
// features, 0 folds and 0.7 % off the truth against 207 folds and 1.5 %.
bool less_distorted(double mx, int fx, double my, int fy, std::size_t samples, bool x_wins_ties = false) {
  if (std::abs(mx - my) > 0.05 * std::min(mx, my)) return mx < my;
  if (std::abs(fx - fy) > 0.005 * double(samples)) return fx < fy;
  return x_wins_ties || mx < my;
}

bool less_distorted(const IntersurfaceResult& x, const IntersurfaceResult& y, std::size_t samples,
                    bool x_wins_ties = false) {
  return less_distorted(summed_median(x), summed_folds(x), summed_median(y), summed_folds(y), samples, x_wins_ties);
}

// The stage times of a map computed and dropped, added to the one kept.
void add_stage_seconds(IntersurfaceResult& kept, const IntersurfaceResult& dropped) {
  kept.seconds_features += dropped.seconds_features;
  kept.seconds_partition += dropped.seconds_partition;
  kept.seconds_parameterize += dropped.seconds_parameterize;
  kept.seconds_optimize += dropped.seconds_optimize;
  kept.seconds_locate += dropped.seconds_locate;
  kept.seconds_measure += dropped.seconds_measure;
}

// Genus >= 1: the map through one consistent partition of the closed
// meshes (patch embeddings, their optimization, point location), measured.
void map_partition(ConsistentPartition& partition, const ClosedMesh& closed_a, const ClosedMesh& closed_b,
                   const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                   const IntersurfaceOptions& options, const ProgressCallback& progress) {
  auto stage = Clock::now();
  if (progress && !progress(0, "parameterizing patches")) throw Cancelled();
  PatchParameterization uv_a = parameterize_patches(partition.sides[0], partition);
  const PatchParameterization uv_b = parameterize_patches(partition.sides[1], partition);
  result.seconds_parameterize = seconds_since(stage);

  stage = Clock::now();
  if (progress && !progress(0.3, "optimizing the map")) throw Cancelled();
  const int sweeps = options.optimize_rounds > 0 ? options.optimize_sweeps : 0;
  optimize_patch_map(partition.sides[0], uv_a, partition.sides[1], uv_b, sweeps, options.sphere.threads,
                     sweeps > 0 ? kPatchAreaRounds : 0);
  // Then across the paths (cross_patch_optimization.h).
  CrossPatchMap across(partition, uv_a, uv_b);
  if (options.optimize_rounds > 0)
    across.optimize(options.cross_sweeps, [&](double done) {
      return !progress || progress(0.3 + 0.4 * done, "optimizing the map across the paths");
    });
  result.seconds_optimize = seconds_since(stage);

  stage = Clock::now();
  if (progress && !progress(0.7, "locating vertices on the other mesh")) throw Cancelled();
  const int threads = options.sphere.threads;
  const auto convert = [](const std::vector<InputLocation>& located) {
    std::vector<SurfacePoint> points(located.size());
    for (std::size_t i = 0; i < located.size(); ++i) points[i] = {located[i].triangle, located[i].barycentric};
    return points;
  };
  const TriangleMesh &ca = closed_a.mesh, &cb = closed_b.mesh;
  // The surfaces' own points only (no hole centre, no fan corner); none lands in a fan.
  const auto surface_only = [&](std::vector<SurfacePoint> points, std::size_t count, const TriangleMesh& target) {
    points.resize(count);
    for (const SurfacePoint& p : points)
      if (p.triangle >= int(target.triangles.size())) throw Error("internal error: a surface point maps into a hole");
    return points;
  };
  result.a_to_b = surface_only(convert(across.map_a(cb, threads)), a.vertices.size(), b);
  result.b_to_a = surface_only(convert(across.map_b(ca)), b.vertices.size(), a);
  if (options.corner_images) {
    result.a_corners_to_b = surface_only(convert(across.map_a_corners(ca, cb, threads)), 3 * a.triangles.size(), b);
    result.b_corners_to_a = surface_only(convert(across.map_b_corners(ca, cb, threads)), 3 * b.triangles.size(), a);
  }
  result.a_on_b = surface_positions(b, result.a_to_b);
  result.b_on_a = surface_positions(a, result.b_to_a);
  result.seconds_locate = seconds_since(stage);

  stage = Clock::now();
  result.distortion_a_to_b = result.composition_a_to_b = measure_intersurface_map(a, b, result.a_to_b);
  result.distortion_b_to_a = result.composition_b_to_a = measure_intersurface_map(b, a, result.b_to_a);
  result.seconds_measure = seconds_since(stage);
}

// A pair's consistent partition for the direct map, as traced and with its
// paths moved to balance the patches' areas (`retraced` paths moved), and
// the holes' fans closing both meshes.
struct PatchPartitions {
  ClosedMesh closed_a, closed_b;
  ConsistentPartition traced, balanced;
  int retraced = 0;
  double seconds_features = 0, seconds_partition = 0;
};

// The partitions of the pair (A's paths traced first). A pair given no
// features and without holes starts from the pair of restart `start`.
PatchPartitions partition_pair(const TriangleMesh& a, const TriangleMesh& b, const IntersurfaceResult& result,
                               const IntersurfaceOptions& options, int start, const ProgressCallback& progress) {
  auto stage = Clock::now();
  std::vector<std::array<int, 2>> pairs;
  for (const FeaturePair& f : result.features) pairs.push_back({f.a, f.b});
  // Holes are closed by fans; paths keep cyclic orders by each mesh's own
  // orientation: B is turned like A (its input triangle indices stay, only
  // corner order flips).
  PatchPartitions made{close_holes(a, /*any_genus=*/true), close_holes(b, /*any_genus=*/true), {}, {}, 0, 0, 0};
  const ClosedMesh &closed_a = made.closed_a, &closed_b = made.closed_b;
  if (pairs.empty() && closed_a.loops.empty()) {
    // A's vertex farthest from its centroid (or, restarting, another spread
    // vertex), and B's nearest to it with the centroids and areas matched
    // (meshes posed alike get a matching pair). Holes bring their own pairs
    // on their rims.
    const int far_a = spread_vertex(a, start);
    pairs.push_back({far_a, PathGuide({}, {}, a, b).nearest(a.vertices[far_a], b.vertices)});
  }
  if (result.genus == 0 && pairs.size() == 1 && closed_a.loops.empty()) {
    // A sphere's partition grows from a path: a second pair, A's vertex
    // farthest from the first and B's nearest to it in A's frame (B's
    // farthest from its first if that is the first itself).
    const Vec3 &first_a = a.vertices[pairs[0][0]], &first_b = b.vertices[pairs[0][1]];
    const int far_a = farthest_from(a, first_a);
    int near_b = PathGuide({first_a}, {first_b}, a, b).nearest(a.vertices[far_a], b.vertices);
    if (near_b == pairs[0][1]) near_b = farthest_from(b, first_b);
    pairs.push_back({far_a, near_b});
  }
  TriangleMesh b_like_a = closed_b.mesh;
  const bool turned = signed_volume(closed_a.mesh) * signed_volume(closed_b.mesh) < 0;
  if (turned)
    for (Triangle& t : b_like_a.triangles) std::swap(t[1], t[2]);
  PartitionHoles holes;
  if (!closed_a.loops.empty() || !closed_b.loops.empty()) {
    std::vector<Vec3> on_a, on_b;
    for (const auto& p : pairs) on_a.push_back(a.vertices[p[0]]), on_b.push_back(b.vertices[p[1]]);
    holes.rims = pair_hole_rims(closed_a, closed_b, pairs, turned, PathGuide(on_a, on_b, a, b));
    holes.first_fan = {closed_a.input_triangles, closed_b.input_triangles};
    for (const HoleRim& rim : holes.rims) {
      for (const auto& f : rim.features)
        if (std::find(pairs.begin(), pairs.end(), f) == pairs.end()) pairs.push_back(f);
      pairs.push_back(rim.centre);
    }
  }
  made.seconds_features = seconds_since(stage);

  stage = Clock::now();
  if (progress && !progress(0.05, "partitioning")) throw Cancelled();
  made.traced = consistent_partition(closed_a.mesh, b_like_a, pairs, result.genus, holes);
  // Balancing is an improvement the traced partition can do without: if it fails, that serves.
  made.balanced = made.traced;
  try {
    made.retraced = balance_patch_areas(made.balanced, options.balance_rounds).retraced;
  } catch (const Error&) {
    // retraced stays 0: the partition as traced serves
  }
  made.seconds_partition = seconds_since(stage);
  return made;
}

// The direct map through a consistent partition (every pair of genus >= 1;
// genus 0 on request or to compare with the sphere): through the partition
// as traced and through the balanced one (when any path moved), the lower
// summed median distortion kept, as for genus 0's restarts. With
// `partitions`, the pair's partitions from `start` (see partition_pair) are
// taken from there, or traced and left there when it is empty; the maps
// refine copies of them.
void map_through_patches(const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                         const IntersurfaceOptions& options, int start, const ProgressCallback& progress,
                         std::shared_ptr<const PatchPartitions>* partitions = nullptr) {
  if (partitions && !*partitions)
    *partitions = std::make_shared<const PatchPartitions>(partition_pair(a, b, result, options, start, progress));
  PatchPartitions made = partitions ? **partitions : partition_pair(a, b, result, options, start, progress);
  const ClosedMesh &closed_a = made.closed_a, &closed_b = made.closed_b;
  const int given = int(result.features.size()), retraced = made.retraced;
  ConsistentPartition partition = std::move(made.traced), balanced = std::move(made.balanced);
  result.seconds_features = made.seconds_features;
  result.seconds_partition = made.seconds_partition;
  result.patch_area_ratio = patch_area_ratio(partition);
  map_partition(partition, closed_a, closed_b, a, b, result, options, slice(progress, 0.6, retraced ? 0.8 : 1));
  if (retraced > 0) {
    IntersurfaceResult moved = result;
    bool mapped = true;
    try {
      map_partition(balanced, closed_a, closed_b, a, b, moved, options, slice(progress, 0.8, 1));
    } catch (const Cancelled&) {
      throw;
    } catch (const Error&) {
      mapped = false;
    }
    const bool better = mapped && less_distorted(moved, result, a.triangles.size() + b.triangles.size());
    // Both maps share the partition and features: their times count once.
    IntersurfaceResult& kept = better ? moved : result;
    const double partition_seconds = kept.seconds_partition, feature_seconds = kept.seconds_features;
    add_stage_seconds(kept, better ? result : moved);
    kept.seconds_partition = partition_seconds, kept.seconds_features = feature_seconds;
    if (better) {
      result = std::move(moved);
      result.balanced_patches = true;
      result.patch_area_ratio = patch_area_ratio(balanced);
      partition = std::move(balanced);
    }
  }

  const std::vector<int>&fa = partition.sides[0].feature_vertex, &fb = partition.sides[1].feature_vertex;
  result.features.clear();
  for (std::size_t k = 0; k < fa.size(); ++k)
    if (int(k) < given || (fa[k] < int(a.vertices.size()) && fb[k] < int(b.vertices.size())))
      result.features.push_back({fa[k], fb[k]});
  result.added_features = int(result.features.size()) - given;
  result.base_vertices = int(fa.size());
  result.base_triangles = int(partition.triangles.size());
  result.steiner_a = partition.sides[0].mesh.vertex_count() - int(closed_a.mesh.vertices.size());
  result.steiner_b = partition.sides[1].mesh.vertex_count() - int(closed_b.mesh.vertices.size());
}

// Vertices no triangle uses (the teapot has 4) carry no surface: the map is
// computed without them, and each takes the image of the nearest used vertex.
struct UsedVertices {
  TriangleMesh mesh;         // the used vertices only, triangles in their order
  std::vector<int> to_used;  // per input vertex: its index in `mesh`, -1 if unused
  std::vector<int> nearest;  // per input vertex: the nearest used input vertex (itself if used)
};

// Null when every vertex is used (or an index is out of range: check_mesh reports that).
std::optional<UsedVertices> drop_unused(const TriangleMesh& mesh) {
  const int n = int(mesh.vertices.size());
  std::vector<char> used(n, 0);
  for (const Triangle& t : mesh.triangles)
    for (int v : t) {
      if (v < 0 || v >= n) return std::nullopt;
      used[v] = 1;
    }
  if (std::count(used.begin(), used.end(), 1) == n) return std::nullopt;
  UsedVertices u;
  u.to_used.assign(n, -1);
  for (int v = 0; v < n; ++v)
    if (used[v]) u.to_used[v] = int(u.mesh.vertices.size()), u.mesh.vertices.push_back(mesh.vertices[v]);
  for (Triangle t : mesh.triangles) {
    for (int& v : t) v = u.to_used[v];
    u.mesh.triangles.push_back(t);
  }
  u.nearest.resize(n);
  for (int v = 0; v < n; ++v) {
    u.nearest[v] = v;
    double best = std::numeric_limits<double>::infinity();
    for (int w = 0; !used[v] && w < n; ++w)
      if (used[w] && (mesh.vertices[w] - mesh.vertices[v]).squaredNorm() < best)
        best = (mesh.vertices[w] - mesh.vertices[v]).squaredNorm(), u.nearest[v] = w;
  }
  return u;
}

// How a restart lays out the pair's consistent parameterization (see
// IntersurfaceOptions::restarts).
enum class PairLayout { single_pass, carried_guides, aligned };

// Genus 0: the composition of a consistent spherical parameterization of
// the pair, refitted and optimized for symmetric distortion (see the options).
void map_through_sphere_pair(const TriangleMesh& a, const TriangleMesh& b, const std::vector<FeaturePair>& features,
                             PairLayout layout, IntersurfaceResult& result, const IntersurfaceOptions& options,
                             const ProgressCallback& progress) {
  // Too few pairs for a constrained map: add some from the aligned unconstrained maps.
  auto stage = Clock::now();
  if (features.size() < 3) {
    add_features(a, b, result.features, 4, options.sphere, slice(progress, 0, 0.2));
    result.added_features = int(result.features.size() - features.size());
  }
  result.seconds_features = seconds_since(stage);

  stage = Clock::now();
  std::vector<ConsistentMember> members{{a, {}}, {b, {}}};
  for (const FeaturePair& f : result.features) members[0].features.push_back(f.a), members[1].features.push_back(f.b);
  ConsistentOptions consistent;
  consistent.sphere = options.sphere;
  consistent.grid = options.grid;
  consistent.carry_guides = layout != PairLayout::single_pass;
  consistent.align = layout == PairLayout::aligned;  // B's map refitted towards A's: the refits below would repeat it
  const ConsistentResult maps = consistent_spherical_parameterization(
      members, consistent, slice(progress, features.size() < 3 ? 0.2 : 0, 0.7));
  result.seconds_parameterize = seconds_since(stage);
  ConstrainedResult map_a = maps.members[0], map_b = maps.members[1];  // the optimization moves their sphere points
  std::vector<std::pair<int, int>> a_to_b, b_to_a;
  for (const FeaturePair& f : result.features) a_to_b.push_back({f.a, f.b}), b_to_a.push_back({f.b, f.a});
  const int threads = options.sphere.threads;
  const auto compose = [&] {
    result.a_to_b = map_through_sphere(map_a.sphere, b, map_b, a_to_b, threads);
    result.b_to_a = map_through_sphere(map_b.sphere, a, map_a, b_to_a, threads);
  };
  const auto measure = [&](MapDistortion& forward, MapDistortion& backward) {
    forward = measure_intersurface_map(a, b, result.a_to_b);
    backward = measure_intersurface_map(b, a, result.b_to_a);
  };
  // With holes, no refit: it does not keep boundary vertices on their arcs.
  const bool closed = map_a.holes == 0 && map_b.holes == 0;
  const bool refit = options.correspondence_weight > 0 && closed && layout != PairLayout::aligned;
  const bool optimize = options.optimize_rounds > 0 && options.optimize_sweeps > 0;

  stage = Clock::now();
  if (refit || optimize) {
    compose();
    measure(result.composition_a_to_b, result.composition_b_to_a);
  }
  if (refit) {
    // Each map again, now also consistent with the other's (coarse to fine):
    // A's against B's, then B's against the new A's. Each is kept only if
    // the median energy, both directions summed, drops: the means rank maps
    // by their few worst triangles (and a copy of B is already exact).
    // Refitting only A left the finer mesh's distortion where the stretch
    // energy put it (cow - horse, final map: B -> A 12.1, medians 5.8 / 5.3;
    // refitting B too: 6.7, medians 5.2 / 4.8).
    double median = result.composition_a_to_b.median_symmetric_dirichlet +
                    result.composition_b_to_a.median_symmetric_dirichlet;
    for (int side = 0; side < 2; ++side) {
      ConstrainedResult& map = side == 0 ? map_a : map_b;
      const ConstrainedResult before = map;
      const ParameterizedSurface other = side == 0 ? parameterized_surface(b, map_b) : parameterized_surface(a, map_a);
      map = parameterize_to_locations(members[side], maps.feature_locations, options.sphere,
                                      slice(progress, 0.7 + 0.05 * side, 0.75 + 0.05 * side),
                                      ReferenceMap{&other.surface, &other.sphere, options.correspondence_weight});
      compose();
      MapDistortion forward, backward;
      measure(forward, backward);
      const bool kept = forward.median_symmetric_dirichlet + backward.median_symmetric_dirichlet < median;
      if (kept)
        median = forward.median_symmetric_dirichlet + backward.median_symmetric_dirichlet;
      else
        map = before;
      (side == 0 ? result.refitted_a : result.refitted_b) = kept;
    }
  }
  if (optimize) optimize_composition(a, map_a, b, map_b, result.features, options, slice(progress, 0.8, 0.95));
  result.steiner_a = int(map_a.steiner.size());
  result.steiner_b = int(map_b.steiner.size());
  result.seconds_optimize = seconds_since(stage);
  for (const auto& [mesh, map, efficiency] :
       {std::tuple<const TriangleMesh&, const ConstrainedResult&, double&>{a, map_a, result.efficiency_a},
        {b, map_b, result.efficiency_b}}) {
    const ParameterizedSurface p = parameterized_surface(mesh, map);
    const SphericalMapReport report = measure_spherical_map(p.surface, p.sphere);
    efficiency = report.efficiency;
    result.sphere_flipped += report.flipped;
  }

  stage = Clock::now();
  if (progress && !progress(0.95, "locating vertices on the other mesh")) throw Cancelled();
  compose();
  if (options.corner_images) {
    result.a_corners_to_b = map_through_sphere(corner_directions(a, map_a), b, map_b, {}, threads);
    result.b_corners_to_a = map_through_sphere(corner_directions(b, map_b), a, map_a, {}, threads);
  }
  result.a_on_b = surface_positions(b, result.a_to_b);
  result.b_on_a = surface_positions(a, result.b_to_a);
  result.seconds_locate = seconds_since(stage);

  stage = Clock::now();
  measure(result.distortion_a_to_b, result.distortion_b_to_a);
  if (!refit && !optimize)
    result.composition_a_to_b = result.distortion_a_to_b, result.composition_b_to_a = result.distortion_b_to_a;
  result.seconds_measure = seconds_since(stage);
}

// The same map seen from the other side: A and B exchanged.
void exchange_sides(IntersurfaceResult& r) {
  std::swap(r.a_to_b, r.b_to_a);
  std::swap(r.a_corners_to_b, r.b_corners_to_a);
  std::swap(r.a_on_b, r.b_on_a);
  std::swap(r.distortion_a_to_b, r.distortion_b_to_a);
  std::swap(r.composition_a_to_b, r.composition_b_to_a);
  for (FeaturePair& f : r.features) std::swap(f.a, f.b);
  std::swap(r.efficiency_a, r.efficiency_b);
  std::swap(r.refitted_a, r.refitted_b);
  std::swap(r.steiner_a, r.steiner_b);
}

// Of two maps computed side by side, the one to keep, left in `first`: a
// cancellation is rethrown, a map whose computation failed leaves the other
// (both failed: first's error rethrown), else the less distorted wins (a
// tie goes to `second` when `second_wins_ties`), the other's stage times added.
void keep_less_distorted(IntersurfaceResult& first, const std::exception_ptr& first_error,
                         IntersurfaceResult& second, const std::exception_ptr& second_error, std::size_t samples,
                         bool second_wins_ties = false) {
  const bool first_failed = failed_with_error(first_error), second_failed = failed_with_error(second_error);
  if (first_failed && second_failed) std::rethrow_exception(first_error);
  if (second_failed) return;
  if (first_failed) {
    first = std::move(second);
    return;
  }
  const bool second_wins = less_distorted(second, first, samples, second_wins_ties);
  add_stage_seconds(second_wins ? second : first, second_wins ? first : second);
  if (second_wins) first = std::move(second);
}

// The partitions of one start from both sides (see map_through_patches).
struct StartPartitions {
  int start = -1;
  std::array<std::shared_ptr<const PatchPartitions>, 2> sides;  // from A's side, from B's side
};

// The direct map through a partition, traced and optimized from A's side and
// from B's side at once, the less distorted kept: the partition is
// traced on A first and A's embedding moves against B's, so the two differ
// (sets/cactus 2 -> 0, 10 features: 1.1 % off the truth one way, 0.6 % the
// other), and the map kept does not depend on which mesh is called A.
// `partitions`: each side's partitions, as map_through_patches takes them.
void map_directly_from(const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                       const IntersurfaceOptions& options, int start, const ProgressCallback& progress,
                       StartPartitions* partitions = nullptr) {
  IntersurfaceResult backward = result;
  exchange_sides(backward);
  const auto side = [&](int k) { return partitions ? &partitions->sides[k] : nullptr; };
  const auto [forward_error, backward_error] = run_side_by_side(
      progress, 0.5,
      [&](const ProgressCallback& part) { map_through_patches(a, b, result, options, start, part, side(0)); },
      [&](const ProgressCallback& part) { map_through_patches(b, a, backward, options, start, part, side(1)); });
  if (!backward_error) exchange_sides(backward);
  keep_less_distorted(result, forward_error, backward, backward_error, a.triangles.size() + b.triangles.size());
}

// Per start tried: the start, both directions' summed mean and median, and folds.
struct StartTrials {
  std::vector<int> starts;
  std::vector<double> energies, medians;
  std::vector<int> folds;
};

// Direct maps from each of `starts` (see map_through_patches), the least
// distorted kept in `result` and each one's summed mean, median and folds
// appended to `tried` (in order, with its start). A start that fails is
// skipped; when all fail, the first error is thrown. `partitions` holds the
// partitions of its start when that is among `starts` (they are not traced
// again), and is left holding those of the start kept.
void map_directly_best_of(const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                          const IntersurfaceOptions& options, const std::vector<int>& starts, StartTrials& tried,
                          StartPartitions& partitions, const ProgressCallback& progress) {
  IntersurfaceResult best;
  std::exception_ptr error;
  bool found = false;
  StartPartitions kept;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    IntersurfaceResult map = result;
    StartPartitions made = partitions.start == starts[k] ? partitions : StartPartitions{starts[k], {}};
    try {
      map_directly_from(a, b, map, options, starts[k],
                        slice(progress, double(k) / starts.size(), (k + 1.0) / starts.size()), &made);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error&) {
      if (!error) error = std::current_exception();
      continue;
    }
    tried.starts.push_back(starts[k]);
    tried.energies.push_back(map.distortion_a_to_b.symmetric_dirichlet + map.distortion_b_to_a.symmetric_dirichlet);
    tried.medians.push_back(summed_median(map));
    tried.folds.push_back(summed_folds(map));
    if (!found || less_distorted(map, best, a.triangles.size() + b.triangles.size()))
      best = std::move(map), kept = std::move(made);
    found = true;
  }
  if (!found) std::rethrow_exception(error);
  result = std::move(best);
  partitions = std::move(kept);
}

// The direct map. A pair given no features and without holes has an
// automatic first pair, which decides how the partition pairs the surfaces'
// handles and parts; between different shapes the maps from different first
// pairs differ widely (kitten - rocker-arm, four: summed medians 22.0, 20.2,
// 14.3, 32.4), and they rank alike before the optimization (28.6, 25.7,
// 18.3, 40.6). So options.starts first pairs are each mapped without
// optimization, and the options.restarts least distorted of them are
// optimized, the least distorted kept.
void map_directly(const TriangleMesh& a, const TriangleMesh& b, IntersurfaceResult& result,
                  const IntersurfaceOptions& options, const ProgressCallback& progress) {
  const bool automatic = result.features.empty() && check_mesh(a).closed() && check_mesh(b).closed();
  if (!automatic) {
    map_directly_from(a, b, result, options, 0, progress);
    return;
  }
  const std::size_t samples = a.triangles.size() + b.triangles.size();
  std::vector<int> starts(std::max(options.starts, options.restarts));
  std::iota(starts.begin(), starts.end(), 0);
  StartTrials screened;
  StartPartitions partitions;  // the screened start kept: its optimization does not trace them again
  double screening = 0;
  if (options.optimize_rounds > 0 && int(starts.size()) > options.restarts) {
    IntersurfaceOptions quick = options;
    quick.optimize_rounds = 0;
    IntersurfaceResult ignored = result;
    screening = 0.4;
    map_directly_best_of(a, b, ignored, quick, starts, screened, partitions, slice(progress, 0, screening));
    // The least distorted of those left, options.restarts times (the tie
    // rule is no ordering to sort by).
    std::vector<int> left(screened.starts.size());
    std::iota(left.begin(), left.end(), 0);
    starts.clear();
    while (int(starts.size()) < options.restarts && !left.empty()) {
      auto best = left.begin();
      for (auto k = left.begin(); k != left.end(); ++k)
        if (less_distorted(screened.medians[*k], screened.folds[*k], screened.medians[*best], screened.folds[*best],
                           samples))
          best = k;
      starts.push_back(screened.starts[*best]);
      left.erase(best);
    }
  }
  StartTrials optimized;
  map_directly_best_of(a, b, result, options, starts, optimized, partitions, slice(progress, screening, 1));
  result.start_median_dirichlet = screened.medians;
  if (optimized.starts.size() > 1) {
    result.restart_dirichlet = std::move(optimized.energies);
    result.restart_median_dirichlet = std::move(optimized.medians);
    result.restart_flipped = std::move(optimized.folds);
  }
}

// Genus 0 through the sphere: options.restarts maps, the least distorted
// kept. The optimization ends in a different local minimum from
// each start; restarts cycle through three layouts of the pair's consistent
// parameterization, the seed advancing after each cycle; each starts some
// pairs in a better basin and others in a worse one.
void map_through_sphere_restarts(const TriangleMesh& a, const TriangleMesh& b, const std::vector<FeaturePair>& features,
                                 IntersurfaceResult& result, const IntersurfaceOptions& options,
                                 const ProgressCallback& progress) {
  constexpr PairLayout kLayouts[] = {PairLayout::single_pass, PairLayout::carried_guides, PairLayout::aligned};
  std::vector<double> energies, medians;
  std::vector<int> folds;
  IntersurfaceResult best;
  for (int r = 0, restarts = options.restarts; r < restarts; ++r) {
    IntersurfaceOptions attempt = options;
    attempt.sphere.seed = options.sphere.seed + r / 3;
    IntersurfaceResult tried = result;
    map_through_sphere_pair(a, b, features, kLayouts[r % 3], tried, attempt,
                            slice(progress, double(r) / restarts, (r + 1.0) / restarts));
    energies.push_back(tried.distortion_a_to_b.symmetric_dirichlet + tried.distortion_b_to_a.symmetric_dirichlet);
    medians.push_back(summed_median(tried));
    folds.push_back(summed_folds(tried));
    if (r == 0 || less_distorted(tried, best, a.triangles.size() + b.triangles.size())) best = std::move(tried);
  }
  result = std::move(best);
  result.restart_dirichlet = std::move(energies);
  result.restart_median_dirichlet = std::move(medians);
  result.restart_flipped = std::move(folds);
}

}  // namespace

std::vector<Vec3> surface_positions(const TriangleMesh& target, const std::vector<SurfacePoint>& points) {
  std::vector<Vec3> positions(points.size(), Vec3::Zero());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& p = points[i];
    if (p.triangle < 0 || p.triangle >= int(target.triangles.size()))
      throw InvalidInput("point " + std::to_string(i) + " lies on triangle " + std::to_string(p.triangle) +
                         " but the target has " + std::to_string(target.triangles.size()) + " triangles");
    for (int k = 0; k < 3; ++k) positions[i] += p.barycentric[k] * target.vertices[target.triangles[p.triangle][k]];
  }
  return positions;
}

const char* method_name(IntersurfaceMethod method) {
  switch (method) {
    case IntersurfaceMethod::sphere: return "sphere";
    case IntersurfaceMethod::partition: return "partition";
    default: return "auto";
  }
}

std::optional<IntersurfaceMethod> parse_method(const std::string& name) {
  for (IntersurfaceMethod m : {IntersurfaceMethod::automatic, IntersurfaceMethod::sphere, IntersurfaceMethod::partition})
    if (name == method_name(m)) return m;
  return std::nullopt;
}

MapDistortion measure_intersurface_map(const TriangleMesh& source, const TriangleMesh& target,
                                       const std::vector<SurfacePoint>& image) {
  if (image.size() != source.vertices.size())
    throw InvalidInput("the map has " + std::to_string(image.size()) + " images for " +
                       std::to_string(source.vertices.size()) + " vertices");
  const std::vector<Vec3> mapped = surface_positions(target, image);
  const double source_area = surface_area(source), target_area = surface_area(target);
  const double scale = target_area > 0 ? std::sqrt(source_area / target_area) : 1;  // target to the source's area
  // Normals of the target, turned to face like the source's when one of the
  // two meshes lists its triangles inwards (judged with their holes closed:
  // an open mesh's volume changes sign with where the origin lies).
  const double facing =
      signed_volume(close_holes(source, true).mesh) * signed_volume(close_holes(target, true).mesh) < 0 ? -1.0 : 1.0;
  const auto normal = [&](int t) {
    const Triangle& c = target.triangles[t];
    return Vec3(facing *
                (target.vertices[c[1]] - target.vertices[c[0]]).cross(target.vertices[c[2]] - target.vertices[c[0]]));
  };

  MapDistortion d;
  double energy = 0, area = 0;
  std::vector<double> energies;  // per source triangle of non-zero area
  energies.reserve(source.triangles.size());
  for (const Triangle& t : source.triangles) {
    const Vec3 &p0 = source.vertices[t[0]], &p1 = source.vertices[t[1]], &p2 = source.vertices[t[2]];
    const Vec3 q0 = scale * mapped[t[0]], q1 = scale * mapped[t[1]], q2 = scale * mapped[t[2]];
    const Vec3 nq = (q1 - q0).cross(q2 - q0);
    const Vec3 surface_normal = normal(image[t[0]].triangle) + normal(image[t[1]].triangle) +
                                normal(image[t[2]].triangle);
    if (nq.dot(surface_normal) < 0) ++d.flipped;
    const Vec3 p[3] = {p0, p1, p2}, q[3] = {q0, q1, q2};
    double ap;
    const double e = symmetric_dirichlet(p, q, &ap);
    if (ap <= 0) continue;  // zero-area source triangles carry no energy
    if (0.5 * nq.norm() <= 1e-14 * source_area) {
      ++d.degenerate;
      energies.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    energy += ap * e;
    area += ap;
    energies.push_back(e);
  }
  d.symmetric_dirichlet = area > 0 ? energy / area : std::numeric_limits<double>::infinity();
  d.median_symmetric_dirichlet = std::numeric_limits<double>::infinity();
  if (!energies.empty()) {
    const auto middle = energies.begin() + energies.size() / 2;
    std::nth_element(energies.begin(), middle, energies.end());
    d.median_symmetric_dirichlet = *middle;
  }
  return d;
}

IntersurfaceResult intersurface_map(const TriangleMesh& a, const TriangleMesh& b,
                                    const std::vector<FeaturePair>& features, const IntersurfaceOptions& options,
                                    const ProgressCallback& progress) {
  const auto start = Clock::now();
  const std::optional<UsedVertices> used_a = drop_unused(a), used_b = drop_unused(b);
  if (used_a || used_b) {
    // The map of the used vertices, then every input vertex's entry from it.
    const auto index = [](const std::optional<UsedVertices>& u, int v) { return u ? u->to_used[u->nearest[v]] : v; };
    check_features(features, a, b);
    std::vector<FeaturePair> used_features;
    for (std::size_t k = 0; k < features.size(); ++k) {
      const FeaturePair& f = features[k];
      for (const auto& [u, v, name] : {std::tuple<const std::optional<UsedVertices>&, int, const char*>{used_a, f.a, "A"},
                                       {used_b, f.b, "B"}})
        if (u && u->to_used[v] < 0)
          throw InvalidInput("feature pair " + std::to_string(k) + ": vertex " + std::to_string(v) + " of " + name +
                             " is used by no triangle");
      used_features.push_back({index(used_a, f.a), index(used_b, f.b)});
    }
    IntersurfaceResult r = intersurface_map(used_a ? used_a->mesh : a, used_b ? used_b->mesh : b, used_features,
                                            options, progress);
    const auto expand = [&](const std::optional<UsedVertices>& u, int n, auto& per_vertex) {
      if (!u) return;
      auto compact = per_vertex;
      per_vertex.resize(n);
      for (int v = 0; v < n; ++v) per_vertex[v] = compact[u->to_used[u->nearest[v]]];
    };
    expand(used_a, int(a.vertices.size()), r.a_to_b);
    expand(used_a, int(a.vertices.size()), r.a_on_b);
    expand(used_b, int(b.vertices.size()), r.b_to_a);
    expand(used_b, int(b.vertices.size()), r.b_on_a);
    // Corner images need nothing: the triangles, their order and corners are kept.
    const auto original = [](const std::optional<UsedVertices>& u, int v) {
      return u ? int(std::find(u->to_used.begin(), u->to_used.end(), v) - u->to_used.begin()) : v;
    };
    for (FeaturePair& f : r.features) f = {original(used_a, f.a), original(used_b, f.b)};
    r.seconds = seconds_since(start);
    return r;
  }
  const int genus_a = checked_genus(a, "A"), genus_b = checked_genus(b, "B");
  if (genus_a != genus_b)
    throw TopologyError("A has genus " + std::to_string(genus_a) + ", B has genus " + std::to_string(genus_b) +
                        "; an inter-surface map needs equal genus");
  check_features(features, a, b);
  IntersurfaceResult result;
  result.genus = genus_a;
  result.features = features;
  if (genus_a == 0)
    for (const auto& [mesh, name] : {std::pair<const TriangleMesh&, const char*>{a, "A"}, {b, "B"}}) {
      try {
        require_sphere_topology(mesh, /*allow_holes=*/true);
      } catch (const TopologyError& e) {
        throw TopologyError(std::string(name) + ": " + e.what());
      } catch (const InvalidInput& e) {
        throw InvalidInput(std::string(name) + ": " + e.what());
      }
    }
  if (options.restarts < 1) throw InvalidInput("restarts must be at least 1, got " + std::to_string(options.restarts));
  if (options.starts < 1) throw InvalidInput("starts must be at least 1, got " + std::to_string(options.starts));
  if (genus_a > 0 && options.method == IntersurfaceMethod::sphere)
    throw InvalidInput("the sphere method maps genus-0 pairs only; A and B have genus " + std::to_string(genus_a));
  if (genus_a > 0 || options.method == IntersurfaceMethod::partition) {
    map_directly(a, b, result, options, progress);
    result.method = IntersurfaceMethod::partition;
    if (genus_a == 0) result.partition_median_dirichlet = summed_median(result);
    if (progress && !progress(1, "done")) throw Cancelled();
    result.seconds = seconds_since(start);
    return result;
  }
  if (options.grid < 2 || options.grid % 2 != 0)
    throw InvalidInput("grid must be even and at least 2, got " + std::to_string(options.grid));

  // Automatic: the direct map too, side by side with the sphere's (a
  // partition that gets stuck leaves the sphere's map, a sphere that refuses
  // a hole ringed by too few pairs the partition's, which pairs holes itself).
  const auto through_sphere = [&](const ProgressCallback& part) {
    map_through_sphere_restarts(a, b, features, result, options, part);
    result.method = IntersurfaceMethod::sphere;
    result.sphere_median_dirichlet = summed_median(result);
  };
  if (options.method == IntersurfaceMethod::sphere) {
    through_sphere(progress);
  } else {
    IntersurfaceResult direct = result;
    const auto [direct_error, sphere_error] = run_side_by_side(
        progress, 0.3, [&](const ProgressCallback& part) { map_directly(a, b, direct, options, part); },
        through_sphere);
    // Either map kept reports both medians and the sphere's restarts.
    if (!direct_error) result.partition_median_dirichlet = summed_median(direct);
    result.start_median_dirichlet = direct.start_median_dirichlet;
    direct.method = IntersurfaceMethod::partition;
    direct.sphere_median_dirichlet = result.sphere_median_dirichlet;
    direct.partition_median_dirichlet = result.partition_median_dirichlet;
    direct.restart_dirichlet = result.restart_dirichlet;
    direct.restart_median_dirichlet = result.restart_median_dirichlet;
    direct.restart_flipped = result.restart_flipped;
    // A tie goes to the direct map: its paths are shortest on both meshes
    // between corresponding features, and where that costs no more
    // distortion than the sphere's free optimization, the paths hold the
    // map to the truth (21 pairs of sets/cactus and sets/faces, 8-12
    // features, one run each: nearer the truth in 18, as near in 2, 0.03 %
    // farther in 1).
    keep_less_distorted(result, sphere_error, direct, direct_error, a.triangles.size() + b.triangles.size(),
                        /*second_wins_ties=*/true);
  }
  if (progress && !progress(1, "done")) throw Cancelled();
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace cmaps
