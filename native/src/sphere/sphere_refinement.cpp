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

std::vector<Vec3> ring_positions(const MeshRefinement& mesh, const std::vector<Vec3>& sphere, int v) {
  std::vector<Vec3> ring;
  for (int w : mesh.ring(v)) ring.push_back(sphere[w]);
  return ring;
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

    const auto start = kernel_point(ring_positions(refinement, sphere, s.removed), sphere[s.kept]);
    if (!start) throw Error("internal error: empty kernel at vertex split " + std::to_string(s.removed));
    sphere[s.removed] = *start;
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
