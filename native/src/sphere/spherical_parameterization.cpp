#include "consistent_maps/spherical_parameterization.h"

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <random>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/progressive_mesh.h"
#include "sphere/spherical_kernel.h"
#include "sphere/stretch_energy.h"
#include "sphere/vertex_optimizer.h"

namespace cmaps {
namespace {

// How hard to work: one row per effort level.
struct Schedule {
  double growth;          // global pass whenever the vertex count grew by this factor
  int pass_sweeps;        // sweeps of an intermediate global pass
  int final_sweeps;       // sweeps of the final global pass
  double tolerance;       // relative displacement that keeps a vertex active
  int split_iterations;   // Newton steps on a new vertex
};

constexpr Schedule kSchedules[] = {
    {2.0, 2, 8, 0.05, 1},
    {1.5, 3, 30, 0.01, 2},
    {1.25, 6, 100, 0.002, 3},
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Same shape, centred, with total area 4 pi: energies and tolerances are then
// independent of the input's position and scale.
std::vector<Vec3> normalized_positions(const TriangleMesh& mesh) {
  double area = 0;
  Vec3 centre = Vec3::Zero();
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const double ta = 0.5 * (b - a).cross(c - a).norm();
    area += ta;
    centre += ta * (a + b + c) / 3;
  }
  if (!(area > 0) || !std::isfinite(area)) throw InvalidInput("mesh has zero surface area");
  centre /= area;
  const double scale = std::sqrt(4 * M_PI / area);
  std::vector<Vec3> x(mesh.vertices.size());
  for (size_t i = 0; i < x.size(); ++i) x[i] = (mesh.vertices[i] - centre) * scale;
  return x;
}

// Maps the four base vertices to a regular tetrahedron, oriented like the
// base triangles, turned by a seeded random rotation.
void place_base(const MeshRefinement& mesh, std::vector<Vec3>& sphere, std::uint64_t seed) {
  std::vector<int> base;
  for (int v = 0; v < static_cast<int>(sphere.size()); ++v)
    if (mesh.vertex_active(v)) base.push_back(v);
  if (base.size() != 4) throw Error("simplification did not reach a tetrahedron");
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  const double s = 1 / std::sqrt(3.0);
  const Vec3 corners[4] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
  for (int i = 0; i < 4; ++i) sphere[base[i]] = rotation * corners[i];
  const Triangle t = mesh.active_triangles().front();
  if (sphere[t[0]].dot(sphere[t[1]].cross(sphere[t[2]])) < 0) std::swap(sphere[base[0]], sphere[base[1]]);
}

std::vector<Vec3> ring_positions(const MeshRefinement& mesh, const std::vector<Vec3>& sphere, int v) {
  std::vector<Vec3> ring;
  for (int w : mesh.ring(v)) ring.push_back(sphere[w]);
  return ring;
}

}  // namespace

SphereResult spherical_parameterization(const TriangleMesh& mesh, const SphereOptions& options,
                                        const ProgressCallback& progress) {
  require_sphere_topology(mesh);
  if (options.effort < 0 || options.effort > 2) throw InvalidInput("effort must be 0, 1 or 2");
  const Schedule& schedule = kSchedules[options.effort];
  const auto start = std::chrono::steady_clock::now();
  SphereResult result;

  const std::vector<Vec3> positions = normalized_positions(mesh);
  const TriangleMesh normalized{positions, mesh.triangles};
  ProgressCallback simplify_progress;
  if (progress) simplify_progress = [&](double f, const std::string& stage) { return progress(0.1 * f, stage); };
  const ProgressiveMesh pm = build_progressive_mesh(normalized, {}, simplify_progress);
  result.seconds_simplify = seconds_since(start);

  const auto optimize_start = std::chrono::steady_clock::now();
  MeshRefinement refinement(pm);
  const std::vector<const std::vector<Vec3>*> geometries{&positions};
  std::vector<FaceWeights> weights(mesh.triangles.size());
  for (size_t f = 0; f < weights.size(); ++f) weights[f] = face_weights(refinement.triangles()[f], geometries);
  std::vector<Vec3> sphere(mesh.vertices.size(), Vec3::Zero());
  place_base(refinement, sphere, options.seed);
  VertexOptimizer optimizer(refinement, weights, sphere, options.threads);
  optimizer.optimize_all(schedule.pass_sweeps, schedule.tolerance);

  const ProgressSlice refine_progress(progress, "refine", 0.1, 0.8);
  double next_pass = refinement.active_vertex_count() * schedule.growth;
  const double total_splits = std::max<size_t>(1, pm.splits.size());
  while (refinement.has_next_split()) {
    const VertexSplit& s = refinement.apply_next_split();
    for (int i = s.changed_begin; i < s.changed_end; ++i) {
      const int f = pm.changed_faces[i];
      weights[f] = face_weights(refinement.triangles()[f], geometries);
    }
    for (int f : {s.face_left, s.face_right}) weights[f] = face_weights(refinement.triangles()[f], geometries);

    const auto start_point = kernel_point(ring_positions(refinement, sphere, s.removed), sphere[s.kept]);
    if (!start_point) throw Error("internal error: empty kernel at vertex split " + std::to_string(s.removed));
    sphere[s.removed] = *start_point;
    optimizer.optimize_vertex(s.removed, schedule.split_iterations);
    for (int w : refinement.ring(s.removed)) optimizer.optimize_vertex(w, 1);
    optimizer.optimize_vertex(s.removed, 1);
    if (refinement.active_vertex_count() >= next_pass) {
      optimizer.optimize_all(schedule.pass_sweeps, schedule.tolerance);
      next_pass = refinement.active_vertex_count() * schedule.growth;
    }
    if (refinement.splits_applied() % 1024 == 0) refine_progress.report(refinement.splits_applied() / total_splits);
  }
  ProgressSlice(progress, "optimize", 0.8, 1.0).report(0);
  optimizer.optimize_all(schedule.final_sweeps, schedule.tolerance);
  ProgressSlice(progress, "optimize", 0.8, 1.0).report(1);
  result.seconds_optimize = seconds_since(optimize_start);

  result.sphere = std::move(sphere);
  result.report = measure_spherical_map(mesh, result.sphere);
  return result;
}

}  // namespace cmaps
