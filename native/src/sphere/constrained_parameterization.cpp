#include "consistent_maps/constrained_parameterization.h"

#include <chrono>
#include <cmath>
#include <set>
#include <string>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/progressive_mesh.h"
#include "paths/editable_mesh.h"
#include "paths/path_network.h"
#include "paths/spherical_triangulation.h"
#include "sphere/sphere_refinement.h"

namespace cmaps {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void validate_features(const TriangleMesh& mesh, const std::vector<int>& features, const std::vector<Vec3>& targets) {
  if (features.size() < 3)
    throw InvalidInput("need at least 3 features, got " + std::to_string(features.size()));
  std::set<int> seen;
  for (int v : features) {
    if (v < 0 || v >= static_cast<int>(mesh.vertices.size()))
      throw InvalidInput("feature vertex " + std::to_string(v) + " is out of range (mesh has " +
                         std::to_string(mesh.vertices.size()) + " vertices)");
    if (!seen.insert(v).second) throw InvalidInput("feature vertex " + std::to_string(v) + " is given twice");
  }
  if (targets.empty()) return;
  if (targets.size() != features.size())
    throw InvalidInput("got " + std::to_string(targets.size()) + " targets for " + std::to_string(features.size()) +
                       " features");
  for (size_t i = 0; i < targets.size(); ++i) {
    if (!targets[i].allFinite()) throw InvalidInput("target " + std::to_string(i) + " is not finite");
    if (!(targets[i].norm() > 0)) throw InvalidInput("target " + std::to_string(i) + " is the zero vector");
  }
  for (size_t i = 0; i < targets.size(); ++i)
    for (size_t j = i + 1; j < targets.size(); ++j)
      if ((targets[i].normalized() - targets[j].normalized()).norm() < 1e-9)
        throw InvalidInput("targets " + std::to_string(i) + " and " + std::to_string(j) + " are equal");
}

// The vertex farthest from every chosen one: where a free base vertex goes.
int farthest_vertex(const std::vector<Vec3>& x, const std::vector<int>& chosen) {
  int best = -1;
  double best_distance = -1;
  for (int v = 0; v < static_cast<int>(x.size()); ++v) {
    double d = std::numeric_limits<double>::infinity();
    for (int c : chosen) d = std::min(d, (x[v] - x[c]).squaredNorm());
    if (d > best_distance) {
      best_distance = d;
      best = v;
    }
  }
  return best;
}

Vec3 on_surface(const SurfacePoint& p, const std::vector<Vec3>& vertices) {
  Vec3 x = Vec3::Zero();
  for (int s = 0; s < 3; ++s)
    if (p.vertices[s] >= 0) x += p.weights[s] * vertices[p.vertices[s]];
  return x;
}

// The triangulation of the base vertices: the Delaunay triangulation of
// where the guide puts them, which matches the mesh's own shape, when it is
// also a valid triangulation of the targets; otherwise the targets' own.
std::vector<Triangle> feature_layout(const std::vector<Vec3>& points, const std::vector<int>& base_vertices,
                                     const std::vector<Vec3>& guide) {
  std::vector<Vec3> guided;
  for (int v : base_vertices) guided.push_back(guide[v]);
  if (const auto natural = convex_hull_on_sphere(guided)) {
    bool valid = true;
    for (const Triangle& t : *natural) {
      const Vec3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
      valid = valid && a.dot(b.cross(c)) > 1e-9 * (b - a).cross(c - a).norm();
    }
    if (valid) return *natural;
  }
  const auto hull = convex_hull_on_sphere(points);
  if (!hull) throw Error("internal error: targets are coplanar after adding free vertices");
  return *hull;
}

}  // namespace

ConstrainedResult constrained_spherical_parameterization(const TriangleMesh& mesh, const std::vector<int>& features,
                                                         const std::vector<Vec3>& given_targets,
                                                         const SphereOptions& options,
                                                         const ProgressCallback& progress) {
  require_sphere_topology(mesh);
  validate_features(mesh, features, given_targets);
  if (options.effort < 0 || options.effort > 2) throw InvalidInput("effort must be 0, 1 or 2");
  ConstrainedResult result;
  const int n = static_cast<int>(mesh.vertices.size());
  const int k = static_cast<int>(features.size());

  // Work on an outward-oriented, normalized copy, so that the layout on the
  // mesh and on the sphere turn the same way.
  std::vector<Vec3> positions = normalized_positions(mesh.vertices, mesh.triangles);
  std::vector<Triangle> triangles = mesh.triangles;
  const bool inverted = signed_volume({positions, triangles}) < 0;
  if (inverted)
    for (Triangle& t : triangles) std::swap(t[1], t[2]);

  // The unconstrained map guides the paths (below) and, without given
  // targets, provides them (step 1 of the thesis); a quick one suffices as a
  // guide alone.
  SphereOptions guide_options = options;
  if (!given_targets.empty()) guide_options.effort = 0;
  ProgressCallback unconstrained;
  if (progress) unconstrained = [&](double f, const std::string& stage) { return progress(0.3 * f, stage); };
  const SphereResult guide = spherical_parameterization({mesh.vertices, triangles}, guide_options, unconstrained);
  const double begin = 0.3;
  if (given_targets.empty()) {
    for (int v : features) result.targets.push_back(guide.sphere[v]);
  } else {
    for (const Vec3& t : given_targets) result.targets.push_back(t.normalized());
  }
  const auto paths_start = std::chrono::steady_clock::now();

  // Free base vertices until the targets' hull encloses the centre, so every
  // base triangle is smaller than a hemisphere.
  std::vector<Vec3> points = result.targets;
  std::vector<int> base_vertices = features;
  while (const auto extra = point_to_enclose_origin(points)) {
    if (++result.auxiliary_vertices > 8) throw Error("internal error: cannot enclose the centre");
    points.push_back(*extra);
    base_vertices.push_back(farthest_vertex(guide.sphere, base_vertices));
  }
  const std::vector<Triangle> layout = feature_layout(points, base_vertices, guide.sphere);

  // Paths are traced in the guide's metric: there they follow great-circle
  // arcs, so they pass features on the same side as the arcs between the
  // targets do whenever the targets are laid out like the guide (no swirls).
  EditableMesh editable({guide.sphere, triangles});
  const PathNetwork network =
      trace_path_network(editable, base_vertices, points, layout, ProgressSlice(progress, "paths", begin, begin + 0.1));
  result.retraced_paths = network.retraced;
  result.layout_flips = network.flips;
  result.seconds_paths = seconds_since(paths_start);

  // Simplify down to the features, collapsing path vertices along their paths.
  const auto simplify_start = std::chrono::steady_clock::now();
  TriangleMesh refined{std::vector<Vec3>(editable.vertex_count()), editable.triangles()};
  for (int v = 0; v < editable.vertex_count(); ++v) refined.vertices[v] = on_surface(editable.surface_point(v), positions);
  SimplificationOptions simplification;
  simplification.locked.assign(refined.vertices.size(), 0);
  for (int v : base_vertices) simplification.locked[v] = 1;
  for (const auto& path : network.paths)
    for (size_t i = 0; i + 1 < path.size(); ++i) simplification.path_edges.push_back({path[i], path[i + 1]});
  simplification.target_vertices = static_cast<int>(base_vertices.size());
  ProgressCallback simplify_progress;
  if (progress)
    simplify_progress = [&](double f, const std::string& stage) { return progress(begin + 0.1 + 0.1 * f, stage); };
  const ProgressiveMesh pm = build_progressive_mesh(refined, simplification, simplify_progress);
  if (pm.base_vertex_count() != static_cast<int>(base_vertices.size()))
    throw Error("internal error: constrained simplification stopped at " + std::to_string(pm.base_vertex_count()) +
                " vertices instead of " + std::to_string(base_vertices.size()));
  result.seconds_simplify = seconds_since(simplify_start);

  // The base is the targets' triangulation: place it and refine.
  const auto optimize_start = std::chrono::steady_clock::now();
  std::vector<Vec3> sphere(refined.vertices.size(), Vec3::Zero());
  for (size_t i = 0; i < base_vertices.size(); ++i) sphere[base_vertices[i]] = points[i];
  for (size_t f = 0; f < pm.base_triangles.size(); ++f) {
    if (!pm.base_face_active[f]) continue;
    const Triangle& t = pm.base_triangles[f];
    if (!(sphere[t[0]].dot(sphere[t[1]].cross(sphere[t[2]])) > 0))
      throw Error("internal error: base triangle does not match the targets' triangulation");
  }
  std::vector<char> fixed(refined.vertices.size(), 0);
  for (int v : features) fixed[v] = 1;
  refine_on_sphere(pm, {&refined.vertices}, fixed, options, sphere,
                   ProgressSlice(progress, "refine", begin + 0.2, 1.0));
  result.seconds_optimize = seconds_since(optimize_start);

  result.triangles = editable.triangles();
  for (int f = 0; f < static_cast<int>(result.triangles.size()); ++f)
    result.input_triangle.push_back(editable.input_triangle(f));
  if (inverted)
    for (Triangle& t : result.triangles) std::swap(t[1], t[2]);
  // Measure on the refined triangulation with original coordinates.
  TriangleMesh measured{std::vector<Vec3>(sphere.size()), result.triangles};
  for (int v = 0; v < static_cast<int>(sphere.size()); ++v)
    measured.vertices[v] = on_surface(editable.surface_point(v), mesh.vertices);
  // An inverted input maps with the opposite orientation: measure it mirrored.
  std::vector<Vec3> oriented = sphere;
  if (inverted)
    for (Vec3& p : oriented) p.x() = -p.x();
  result.report = measure_spherical_map(measured, inverted ? oriented : sphere);
  for (int i = 0; i < k; ++i)
    result.max_constraint_error = std::max(result.max_constraint_error, (sphere[features[i]] - result.targets[i]).norm());
  result.sphere.assign(sphere.begin(), sphere.begin() + n);
  for (int v = n; v < static_cast<int>(sphere.size()); ++v) {
    const SurfacePoint& p = editable.surface_point(v);
    result.steiner.push_back({p.vertices, p.weights, sphere[v]});
  }
  return result;
}

}  // namespace cmaps
