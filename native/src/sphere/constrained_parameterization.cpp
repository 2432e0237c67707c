#include "consistent_maps/constrained_parameterization.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "common/stage_clock.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/progressive_mesh.h"
#include "paths/editable_mesh.h"
#include "paths/mesh_holes.h"
#include "paths/path_network.h"
#include "paths/spherical_triangulation.h"
#include "sphere/consistent_constrained_parameterization.h"
#include "sphere/sphere_refinement.h"

namespace cmaps {
namespace {

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
int farthest_vertex(const std::vector<Vec3>& x, const std::vector<int>& chosen, const std::vector<char>& excluded) {
  int best = -1;
  double best_distance = -1;
  for (int v = 0; v < static_cast<int>(x.size()); ++v) {
    if (excluded[v]) continue;
    double d = std::numeric_limits<double>::infinity();
    for (int c : chosen) d = std::min(d, (x[v] - x[c]).squaredNorm());
    if (d > best_distance) {
      best_distance = d;
      best = v;
    }
  }
  return best;
}

Vec3 on_surface(const InputPoint& p, const std::vector<Vec3>& vertices) {
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
  return constrained_spherical_parameterization(mesh, features, given_targets, options, progress, ReferenceMap{});
}

ConstrainedResult constrained_spherical_parameterization(const TriangleMesh& mesh, const std::vector<int>& features,
                                                         const std::vector<Vec3>& given_targets,
                                                         const SphereOptions& options,
                                                         const ProgressCallback& progress,
                                                         const ReferenceMap& reference,
                                                         const std::vector<Vec3>* given_guide) {
  // Holes (thesis 3.5) are closed by a temporary centre vertex each; each
  // hole must be ringed by at least 3 features.
  ClosedMesh closed = close_holes(mesh);
  validate_features(mesh, features, given_targets);
  if (options.effort < 0 || options.effort > 2) throw InvalidInput("effort must be 0, 1 or 2");
  std::vector<std::vector<int>> hole_rings = hole_features(closed, features);
  ConstrainedResult result;
  const int n = static_cast<int>(mesh.vertices.size());
  const int k = static_cast<int>(features.size());
  const int holes = static_cast<int>(closed.loops.size());
  const int nc = n + holes;  // vertices of the closed mesh
  result.holes = holes;

  // Maps turn like the mesh's own triangles (as unconstrained maps do), so
  // targets taken from an unconstrained map of the same mesh always fit.
  std::vector<Vec3> positions = normalized_positions(closed.mesh.vertices, closed.mesh.triangles);
  const std::vector<Triangle>& triangles = closed.mesh.triangles;

  // The unconstrained map guides the paths (below) and, without given
  // targets, provides them (step 1 of the thesis); a quick one suffices as a
  // guide alone.
  SphereOptions guide_options = options;
  if (!given_targets.empty()) guide_options.effort = 0;
  ProgressCallback unconstrained;
  if (progress) unconstrained = [&](double f, const std::string& stage) { return progress(0.3 * f, stage); };
  if (given_guide && (given_targets.empty() || given_guide->size() != static_cast<size_t>(nc)))
    throw Error("internal error: a guide needs targets and one direction per vertex of the closed mesh");
  SphereResult guide;
  if (given_guide)
    guide.sphere = *given_guide;
  else
    guide = spherical_parameterization({closed.mesh.vertices, triangles}, guide_options, unconstrained);
  const double begin = 0.3;
  if (given_targets.empty()) {
    for (int v : features) result.targets.push_back(guide.sphere[v]);
  } else {
    for (const Vec3& t : given_targets) result.targets.push_back(t.normalized());
  }
  const auto paths_start = std::chrono::steady_clock::now();

  // Base vertices: the features, one centre per hole (at the mean of its
  // features' targets), then free vertices until the hull encloses the
  // centre of the sphere, so every base triangle is smaller than a hemisphere.
  std::vector<Vec3> points = result.targets;
  std::vector<int> base_vertices = features;
  std::vector<char> excluded(nc, 0);  // boundary vertices and centres: never auxiliary
  for (int h = 0; h < holes; ++h) {
    Vec3 mean = Vec3::Zero();
    for (int f : hole_rings[h]) mean += result.targets[f];
    if (!(mean.norm() > 1e-9))
      throw InvalidInput("the targets of the features ringing hole " + std::to_string(h) + " average to zero");
    points.push_back(mean.normalized());
    base_vertices.push_back(closed.centre(h));
    excluded[closed.centre(h)] = 1;
    for (int v : closed.loops[h]) excluded[v] = 1;
  }
  while (const auto extra = point_to_enclose_origin(points)) {
    if (++result.auxiliary_vertices > 8) throw Error("internal error: cannot enclose the centre");
    points.push_back(*extra);
    base_vertices.push_back(farthest_vertex(guide.sphere, base_vertices, excluded));
  }
  std::vector<Triangle> layout = feature_layout(points, base_vertices, guide.sphere);
  // Each hole is a fan on the sphere too: its polygon's edges and spokes.
  std::vector<std::array<int, 2>> required;
  for (int h = 0; h < holes; ++h) {
    const auto& ring = hole_rings[h];
    for (size_t j = 0; j < ring.size(); ++j) required.push_back({ring[j], ring[(j + 1) % ring.size()]});
    for (int f : ring) required.push_back({k + h, f});
  }
  if (!required.empty()) {
    if (!force_edges(points, layout, required)) {
      const auto hull = convex_hull_on_sphere(points);
      layout = *hull;
      if (!force_edges(points, layout, required))
        throw InvalidInput("the targets of the features ringing the holes cannot be joined around the holes "
                           "without crossing (are they in the order the features run along each hole?)");
    }
    std::set<Triangle> faces(layout.begin(), layout.end());
    auto has = [&](int a, int b, int c) {
      return faces.count({a, b, c}) || faces.count({b, c, a}) || faces.count({c, a, b});
    };
    for (int h = 0; h < holes; ++h) {
      const auto& ring = hole_rings[h];
      for (size_t j = 0; j < ring.size(); ++j)
        if (!has(k + h, ring[j], ring[(j + 1) % ring.size()]))
          throw InvalidInput("the targets of the " + std::to_string(ring.size()) + " features ringing hole " +
                             std::to_string(h) +
                             " do not enclose an empty region in the order the features run along the hole");
    }
  }

  // The hole boundaries between consecutive features and the spokes from
  // the centres to them are given paths; the rest are traced in the guide's
  // metric, where they follow great-circle arcs, so they pass features on the
  // same side as the arcs between the targets do whenever the targets are
  // laid out like the guide (no swirls).
  std::vector<std::vector<int>> prelaid;
  RefineExtras extras;
  for (int h = 0; h < holes; ++h) {
    const auto& loop = closed.loops[h];
    std::vector<size_t> at;
    for (size_t j = 0; j < loop.size(); ++j)
      for (int f : hole_rings[h])
        if (features[f] == loop[j]) at.push_back(j);
    for (size_t j = 0; j < at.size(); ++j) {
      std::vector<int> chain;
      for (size_t i = at[j];; i = (i + 1) % loop.size()) {
        chain.push_back(loop[i]);
        if (i == at[(j + 1) % at.size()] && chain.size() > 1) break;
      }
      prelaid.push_back(chain);
      extras.arcs.chains.push_back(chain);
      prelaid.push_back({closed.centre(h), loop[at[j]]});
    }
  }
  EditableMesh editable({guide.sphere, triangles});
  if (holes > 0) {
    // An edge between two non-consecutive vertices of one boundary chain
    // (e.g. across an ear) would be degenerate on the arc: split it.
    std::vector<std::vector<std::pair<int, int>>> at(nc);  // vertex -> (chain, position)
    for (int c = 0; c < static_cast<int>(extras.arcs.chains.size()); ++c)
      for (int i = 0; i < static_cast<int>(extras.arcs.chains[c].size()); ++i)
        at[extras.arcs.chains[c][i]].push_back({c, i});
    auto chord = [&](int a, int b) {
      if (a >= nc || b >= nc) return false;
      for (const auto& [ca, ia] : at[a])
        for (const auto& [cb, ib] : at[b])
          if (ca == cb && std::abs(ia - ib) != 1) return true;
      return false;
    };
    const int edges = editable.edge_count();
    std::vector<int> chords;
    for (int e = 0; e < edges; ++e)
      if (chord(editable.edge_vertices(e)[0], editable.edge_vertices(e)[1])) chords.push_back(e);
    for (int e : chords) editable.split_edge(e);
  }
  const PathNetwork network = trace_path_network(editable, base_vertices, points, layout,
                                                 ProgressSlice(progress, "paths", begin, begin + 0.1), prelaid);
  result.retraced_paths = network.retraced;
  result.layout_flips = network.flips;
  result.seconds_paths = seconds_since(paths_start);

  // Simplify down to the features, collapsing path vertices along their paths.
  const auto simplify_start = std::chrono::steady_clock::now();
  TriangleMesh refined{std::vector<Vec3>(editable.vertex_count()), editable.triangles()};
  for (int v = 0; v < editable.vertex_count(); ++v)
    refined.vertices[v] = on_surface(editable.surface_point(v), positions);
  SimplificationOptions simplification;
  simplification.locked.assign(refined.vertices.size(), 0);
  for (int v : base_vertices) simplification.locked[v] = 1;
  for (const auto& path : network.paths)
    for (size_t i = 0; i + 1 < path.size(); ++i) simplification.path_edges.push_back({path[i], path[i + 1]});
  simplification.target_vertices = static_cast<int>(base_vertices.size());
  simplification.chains = extras.arcs.chains;
  ProgressCallback simplify_progress;
  if (progress)
    simplify_progress = [&](double f, const std::string& stage) { return progress(begin + 0.1 + 0.1 * f, stage); };
  const ProgressiveMesh pm = build_progressive_mesh(refined, simplification, simplify_progress);
  if (pm.base_vertex_count() != static_cast<int>(base_vertices.size()))
    throw Error("internal error: constrained simplification stopped at " + std::to_string(pm.base_vertex_count()) +
                " vertices instead of " + std::to_string(base_vertices.size()));
  result.seconds_simplify = seconds_since(simplify_start);

  // The base is the targets' triangulation: place it and refine. Hole
  // boundary vertices move only along their arcs; the fans carry no stretch
  // (only the regularizer), so the holes may shrink.
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
  const int faces = static_cast<int>(refined.triangles.size());
  auto is_fan = [&](int f) { return editable.input_triangle(f) >= closed.input_triangles; };
  if (holes > 0) {
    extras.stretch_free_faces.assign(faces, 0);
    for (int f = 0; f < faces; ++f) extras.stretch_free_faces[f] = is_fan(f);
    extras.arcs.index(static_cast<int>(refined.vertices.size()));
  }
  extras.reference = reference;
  refine_on_sphere(pm, {&refined.vertices}, fixed, options, sphere, ProgressSlice(progress, "refine", begin + 0.2, 1.0),
                   holes > 0 || reference.surface ? &extras : nullptr);
  result.seconds_optimize = seconds_since(optimize_start);

  // Output over the input vertices then the Steiner vertices: the centres
  // (closed-mesh vertices n .. nc - 1) and their fans are left out.
  const int total = static_cast<int>(sphere.size());
  auto out = [&](int v) { return v < n ? v : v >= nc ? v - holes : -1; };
  const int steiner_count = total - nc;
  for (int f = 0; f < faces; ++f) {
    Triangle t = editable.triangles()[f];
    if (is_fan(f)) {
      for (int& v : t) v = v >= n && v < nc ? n + steiner_count + (v - n) : out(v);
      result.hole_triangles.push_back(t);
      continue;
    }
    for (int& v : t) v = out(v);
    result.triangles.push_back(t);
    result.input_triangle.push_back(editable.input_triangle(f));
  }
  for (int h = 0; h < holes; ++h) {
    result.hole_centres_sphere.push_back(sphere[closed.centre(h)]);
    result.hole_centres_position.push_back(closed.mesh.vertices[closed.centre(h)]);
    result.hole_features.push_back(hole_rings[h]);
  }
  result.sphere.assign(sphere.begin(), sphere.begin() + n);
  for (int v = nc; v < total; ++v) {
    const InputPoint& p = editable.surface_point(v);
    for (int w : p.vertices)
      if (w >= n) throw Error("internal error: a Steiner vertex lies on a hole's temporary triangles");
    result.steiner.push_back({p.vertices, p.weights, sphere[v]});
  }
  // Measure on the refined triangulation of the input, original coordinates.
  std::vector<Vec3> out_sphere = result.sphere;
  TriangleMesh measured{std::vector<Vec3>(mesh.vertices), result.triangles};
  for (const SteinerVertex& s : result.steiner) {
    Vec3 x = Vec3::Zero();
    for (int j = 0; j < 3; ++j)
      if (s.vertices[j] >= 0) x += s.weights[j] * mesh.vertices[s.vertices[j]];
    measured.vertices.push_back(x);
    out_sphere.push_back(s.sphere);
  }
  result.report = measure_spherical_map(measured, out_sphere);
  for (int i = 0; i < k; ++i)
    result.max_constraint_error =
        std::max(result.max_constraint_error, (sphere[features[i]] - result.targets[i]).norm());
  return result;
}

}  // namespace cmaps
