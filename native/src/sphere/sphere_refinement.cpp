#include "sphere/sphere_refinement.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "consistent_maps/errors.h"
#include "sphere/spherical_kernel.h"
#include "sphere/stretch_energy.h"
#include "sphere/vertex_optimizer.h"

namespace cmaps {
namespace {

// How hard to work: one row per effort level.
struct Schedule {
  double growth;         // global pass whenever the vertex count grew by this factor
  int pass_sweeps;       // sweeps of an intermediate global pass
  int final_sweeps;      // sweeps of the final global pass
  double tolerance;      // relative displacement that keeps a vertex active
  int split_iterations;  // Newton steps on a new vertex
};

constexpr Schedule kSchedules[] = {
    {2.0, 2, 8, 0.05, 1},
    {1.5, 3, 30, 0.01, 2},
    {1.25, 6, 100, 0.002, 3},
};

bool star_valid(const MeshRefinement& mesh, const std::vector<Vec3>& sphere, int v) {
  const std::vector<int> ring = mesh.ring(v);
  for (size_t i = 0; i < ring.size(); ++i)
    if (!chordal_triangle_valid(sphere[v], sphere[ring[i]], sphere[ring[(i + 1) % ring.size()]])) return false;
  return true;
}

// Puts the split's new vertex strictly inside its kernel. The kernel always
// contains points close to the kept vertex inside the triangles the new
// vertex takes over; when rounding defeats the polygon clipping (kernels of
// width near machine precision), walk towards the kept vertex inside those.
void place_split_vertex(const MeshRefinement& mesh, const VertexSplit& s, std::vector<Vec3>& sphere) {
  const std::vector<int> ring = mesh.ring(s.removed);
  std::vector<Vec3> ring_points;
  for (int w : ring) ring_points.push_back(sphere[w]);
  if (const auto p = kernel_point(ring_points, sphere[s.kept])) {
    sphere[s.removed] = *p;
    if (star_valid(mesh, sphere, s.removed)) return;
  }
  const Vec3 kept = sphere[s.kept];
  for (double t = 0.5; t > 1e-14; t *= 0.25)
    for (size_t i = 0; i < ring.size(); ++i) {
      const Vec3& a = ring_points[i];
      const Vec3& b = ring_points[(i + 1) % ring.size()];
      if (ring[i] == s.kept || ring[(i + 1) % ring.size()] == s.kept) continue;
      sphere[s.removed] = (kept + t * ((a + b + kept) / 3 - kept)).normalized();
      if (star_valid(mesh, sphere, s.removed)) return;
    }
  throw Error("internal error: empty kernel at vertex split " + std::to_string(s.removed));
}

// A chain vertex goes on its arc between its current chain neighbours (one
// of them the kept vertex), at the middle of the longest valid stretch.
// Beside a feature where the arcs turn, a free neighbour may have moved
// across this arc's great circle (legal while the arc was one chord): then
// no point of the arc is valid, so the vertex goes to the middle and such
// neighbours move back into their kernels.
void place_on_arc(const MeshRefinement& mesh, const ArcChains& arcs, const std::vector<char>& fixed,
                  const VertexSplit& s, std::vector<Vec3>& sphere) {
  const int v = s.removed;
  const auto [lo, hi] = arcs.neighbours(mesh, v);
  Vec3 origin, axis;
  arcs.frame(sphere, arcs.chain_of[v], origin, axis);
  auto angle = [&](const Vec3& p) { return std::atan2(p.dot(axis), p.dot(origin)); };
  const double t0 = angle(sphere[lo]), t1 = angle(sphere[hi]);
  auto valid_at = [&](double f) {
    const double t = t0 + f * (t1 - t0);
    sphere[v] = std::cos(t) * origin + std::sin(t) * axis;
    return star_valid(mesh, sphere, v);
  };
  constexpr int kSamples = 64;
  int best_begin = -1, best_length = 0;
  for (int i = 1, run = 0; i <= kSamples; ++i) {
    if (i < kSamples && valid_at(double(i) / kSamples)) {
      ++run;
      if (run > best_length) {
        best_length = run;
        best_begin = i - run + 1;
      }
    } else {
      run = 0;
    }
  }
  if (best_length > 0 && valid_at((best_begin + 0.5 * (best_length - 1)) / kSamples)) return;
  // A very thin kernel: close to the kept vertex.
  const bool kept_low = s.kept == lo;
  for (double f = 1.0 / kSamples; f > 1e-15; f *= 0.5)
    if (valid_at(kept_low ? f : 1 - f)) return;
  valid_at(0.5);
  const std::vector<int> ring = mesh.ring(v);
  for (int w : ring) {
    if ((!fixed.empty() && fixed[w]) || arcs.constrained(w) || star_valid(mesh, sphere, w)) continue;
    std::vector<Vec3> around;
    for (int u : mesh.ring(w)) around.push_back(sphere[u]);
    if (const auto p = kernel_point(around, sphere[w])) sphere[w] = *p;
  }
  if (star_valid(mesh, sphere, v) &&
      std::all_of(ring.begin(), ring.end(), [&](int w) { return star_valid(mesh, sphere, w); }))
    return;
  throw Error("internal error: empty kernel on a constrained path at vertex split " + std::to_string(v));
}

}  // namespace

void ArcChains::index(int vertex_count) {
  chain_of.assign(vertex_count, -1);
  index_in_chain.assign(vertex_count, -1);
  for (int c = 0; c < static_cast<int>(chains.size()); ++c)
    for (int i = 1; i + 1 < static_cast<int>(chains[c].size()); ++i) {
      chain_of[chains[c][i]] = c;
      index_in_chain[chains[c][i]] = i;
    }
}

std::pair<int, int> ArcChains::neighbours(const MeshRefinement& mesh, int v) const {
  const std::vector<int>& chain = chains[chain_of[v]];
  int lo = index_in_chain[v] - 1, hi = index_in_chain[v] + 1;
  while (lo > 0 && !mesh.vertex_active(chain[lo])) --lo;
  while (hi + 1 < static_cast<int>(chain.size()) && !mesh.vertex_active(chain[hi])) ++hi;
  return {chain[lo], chain[hi]};
}

void ArcChains::frame(const std::vector<Vec3>& sphere, int chain, Vec3& origin, Vec3& axis) const {
  origin = sphere[chains[chain].front()];
  const Vec3& end = sphere[chains[chain].back()];
  axis = (end - origin * origin.dot(end)).normalized();
}

std::vector<Vec3> normalized_positions(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles) {
  double area = 0;
  Vec3 centre = Vec3::Zero();
  for (const Triangle& t : triangles) {
    const Vec3 &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
    const double ta = 0.5 * (b - a).cross(c - a).norm();
    area += ta;
    centre += ta * (a + b + c) / 3;
  }
  if (!(area > 0) || !std::isfinite(area)) throw InvalidInput("mesh has zero surface area");
  centre /= area;
  const double scale = std::sqrt(4 * M_PI / area);
  std::vector<Vec3> x(vertices.size());
  for (size_t i = 0; i < x.size(); ++i) x[i] = (vertices[i] - centre) * scale;
  return x;
}

void refine_on_sphere(const ProgressiveMesh& pm, const std::vector<const std::vector<Vec3>*>& geometries,
                      const std::vector<char>& fixed, const SphereOptions& options, std::vector<Vec3>& sphere,
                      const ProgressSlice& progress, const RefineExtras* extras) {
  if (options.effort < 0 || options.effort > 2) throw InvalidInput("effort must be 0, 1 or 2");
  const Schedule& schedule = kSchedules[options.effort];
  MeshRefinement refinement(pm);
  std::vector<FaceWeights> weights(pm.base_triangles.size());
  auto update_weights = [&](int f) {
    const bool free = extras && !extras->stretch_free_faces.empty() && extras->stretch_free_faces[f];
    weights[f] = face_weights(refinement.triangles()[f], geometries, free);
  };
  for (size_t f = 0; f < weights.size(); ++f) update_weights(f);
  VertexOptimizer optimizer(refinement, weights, sphere, options.threads);
  optimizer.set_fixed(fixed);
  const ArcChains* arcs = extras && !extras->arcs.chain_of.empty() ? &extras->arcs : nullptr;
  optimizer.set_arcs(arcs);
  std::unique_ptr<CorrespondenceTerm> term;
  if (extras && extras->reference.surface) {
    term = std::make_unique<CorrespondenceTerm>(*geometries[0], 4 * M_PI, extras->reference);  // normalized area
    optimizer.set_correspondence(term.get());
  }
  optimizer.optimize_all(schedule.pass_sweeps, schedule.tolerance);

  double next_pass = refinement.active_vertex_count() * schedule.growth;
  const double total_splits = std::max<size_t>(1, pm.splits.size());
  while (refinement.has_next_split()) {
    const VertexSplit& s = refinement.apply_next_split();
    for (int i = s.changed_begin; i < s.changed_end; ++i) update_weights(pm.changed_faces[i]);
    update_weights(s.face_left);
    update_weights(s.face_right);

    if (arcs && arcs->constrained(s.removed))
      place_on_arc(refinement, *arcs, fixed, s, sphere);
    else
      place_split_vertex(refinement, s, sphere);
    optimizer.optimize_vertex(s.removed, schedule.split_iterations);
    for (int w : refinement.ring(s.removed)) optimizer.optimize_vertex(w, 1);
    optimizer.optimize_vertex(s.removed, 1);

    if (refinement.active_vertex_count() >= next_pass) {
      optimizer.optimize_all(schedule.pass_sweeps, schedule.tolerance);
      next_pass = refinement.active_vertex_count() * schedule.growth;
    }
    if (refinement.splits_applied() % 1024 == 0) progress.report(0.8 * refinement.splits_applied() / total_splits);
  }
  progress.report(0.8);
  optimizer.optimize_all(schedule.final_sweeps, schedule.tolerance);
  progress.report(1.0);
}

}  // namespace cmaps
