#include "intersurface/sphere_route.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <limits>
#include <tuple>

#include "common/stage_clock.h"
#include "consistent/parameterize_with_reference.h"
#include "consistent_maps/consistent_parameterization.h"
#include "consistent_maps/sphere_locator.h"
#include "consistent_maps/stretch_metric.h"
#include "intersurface/map_choice.h"
#include "intersurface/map_distortion.h"
#include "intersurface/sphere_map_optimizer.h"
#include "intersurface/sphere_pair.h"
#include "paths/mesh_holes.h"

namespace cmaps {
namespace {

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

// Adds pairs until there are `wanted`: A's vertices farthest from those
// taken, each with B's nearest on the unconstrained spheres aligned by the
// pairs given.
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
  const double facing_ab = facing(close_holes(a, true).mesh, close_holes(b, true).mesh);
  const auto measure = [&](MapDistortion& forward, MapDistortion& backward) {
    forward = measure_intersurface_map(a, b, result.a_to_b, facing_ab);
    backward = measure_intersurface_map(b, a, result.b_to_a, facing_ab);
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
  result.map_flipped = result.sphere_flipped;  // through the sphere, the map folds where a spherical map does

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

}  // namespace

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

}  // namespace cmaps
