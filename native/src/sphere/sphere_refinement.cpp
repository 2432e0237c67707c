#include "sphere/sphere_refinement.h"

#include <cmath>

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

}  // namespace

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
                      const ProgressSlice& progress) {
  if (options.effort < 0 || options.effort > 2) throw InvalidInput("effort must be 0, 1 or 2");
  const Schedule& schedule = kSchedules[options.effort];
  MeshRefinement refinement(pm);
  std::vector<FaceWeights> weights(pm.base_triangles.size());
  auto update_weights = [&](int f) { weights[f] = face_weights(refinement.triangles()[f], geometries); };
  for (size_t f = 0; f < weights.size(); ++f) update_weights(f);
  VertexOptimizer optimizer(refinement, weights, sphere, options.threads);
  optimizer.set_fixed(fixed);
  optimizer.optimize_all(schedule.pass_sweeps, schedule.tolerance);

  double next_pass = refinement.active_vertex_count() * schedule.growth;
  const double total_splits = std::max<size_t>(1, pm.splits.size());
  while (refinement.has_next_split()) {
    const VertexSplit& s = refinement.apply_next_split();
    for (int i = s.changed_begin; i < s.changed_end; ++i) update_weights(pm.changed_faces[i]);
    update_weights(s.face_left);
    update_weights(s.face_right);

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
