#include "consistent_maps/spherical_parameterization.h"

#include <Eigen/Geometry>
#include <chrono>
#include <random>

#include "common/stage_clock.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/progressive_mesh.h"
#include "sphere/sphere_refinement.h"

namespace cmaps {
namespace {

// Maps the four base vertices to a regular tetrahedron, oriented like the
// base triangles, turned by a seeded random rotation.
void place_base(const ProgressiveMesh& pm, std::vector<Vec3>& sphere, std::uint64_t seed) {
  std::vector<int> base;
  for (int v = 0; v < pm.vertex_count; ++v)
    if (pm.base_vertex_active[v]) base.push_back(v);
  if (base.size() != 4) throw Error("simplification did not reach a tetrahedron");
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  const double s = 1 / std::sqrt(3.0);
  const Vec3 corners[4] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
  for (int i = 0; i < 4; ++i) sphere[base[i]] = rotation * corners[i];
  for (size_t f = 0; f < pm.base_triangles.size(); ++f)
    if (pm.base_face_active[f]) {
      const Triangle& t = pm.base_triangles[f];
      if (sphere[t[0]].dot(sphere[t[1]].cross(sphere[t[2]])) < 0) std::swap(sphere[base[0]], sphere[base[1]]);
      break;
    }
}

}  // namespace

SphereResult spherical_parameterization(const TriangleMesh& mesh, const SphereOptions& options,
                                        const ProgressCallback& progress) {
  return spherical_parameterization(mesh.triangles, {mesh.vertices}, options, progress);
}

SphereResult spherical_parameterization(const std::vector<Triangle>& triangles,
                                        const std::vector<std::vector<Vec3>>& shapes, const SphereOptions& options,
                                        const ProgressCallback& progress) {
  if (shapes.empty()) throw InvalidInput("no shape to parameterize");
  for (const auto& shape : shapes) {
    if (shape.size() != shapes.front().size()) throw InvalidInput("shapes differ in vertex count");
    require_sphere_topology({shape, triangles});
  }
  if (options.effort < 0 || options.effort > 2) throw InvalidInput("effort must be 0, 1 or 2");
  const auto start = std::chrono::steady_clock::now();
  SphereResult result;

  std::vector<std::vector<Vec3>> positions;
  for (const auto& shape : shapes) positions.push_back(normalized_positions(shape, triangles));
  SimplificationOptions simplification;
  simplification.extra_geometries.assign(positions.begin() + 1, positions.end());
  ProgressCallback simplify_progress;
  if (progress) simplify_progress = [&](double f, const std::string& stage) { return progress(0.1 * f, stage); };
  const ProgressiveMesh pm = build_progressive_mesh({positions.front(), triangles}, simplification, simplify_progress);
  result.seconds_simplify = seconds_since(start);

  const auto optimize_start = std::chrono::steady_clock::now();
  std::vector<Vec3> sphere(shapes.front().size(), Vec3::Zero());
  place_base(pm, sphere, options.seed);
  std::vector<const std::vector<Vec3>*> geometries;
  for (const auto& p : positions) geometries.push_back(&p);
  refine_on_sphere(pm, geometries, {}, options, sphere, ProgressSlice(progress, "refine", 0.1, 1.0));
  result.seconds_optimize = seconds_since(optimize_start);

  result.sphere = std::move(sphere);
  result.report = measure_spherical_map({shapes.front(), triangles}, result.sphere);
  return result;
}

}  // namespace cmaps
