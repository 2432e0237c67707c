// Stretch-minimizing spherical parameterization of a closed genus-0 mesh
// (Praun & Hoppe 2003): simplify to a tetrahedron, map it to a regular
// tetrahedron on the sphere, then replay vertex splits coarse to fine, each
// new vertex placed inside its 1-ring kernel and optimized with its
// neighbours, with global optimization sweeps as the mesh grows.
//
// Invariant: every chordal triangle stays positively oriented at every step,
// so the result is bijective.
#pragma once
#include <cstdint>
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/progress.h"
#include "consistent_maps/stretch_metric.h"

namespace cmaps {

struct SphereOptions {
  std::uint64_t seed = 1;  // results are deterministic for a given seed
  int effort = 1;          // 0 = fast preview, 1 = default, 2 = best quality
  int threads = 2;         // worker threads for the global sweeps
};

struct SphereResult {
  std::vector<Vec3> sphere;  // one unit vector per input vertex, input order
  SphericalMapReport report;
  double seconds_simplify = 0;
  double seconds_optimize = 0;
};

// Throws TopologyError / InvalidInput for unsupported input and Cancelled
// when `progress` returns false.
SphereResult spherical_parameterization(const TriangleMesh& mesh, const SphereOptions& options = {},
                                        const ProgressCallback& progress = {});

// One connectivity carrying several shapes (vertex i of every shape
// corresponds; thesis 3.2, step 5): the quadric error and the stretch energy
// are summed over the shapes, each scaled to the same area, so the map suits
// all of them. The report measures the first shape.
SphereResult spherical_parameterization(const std::vector<Triangle>& triangles,
                                        const std::vector<std::vector<Vec3>>& shapes,
                                        const SphereOptions& options = {}, const ProgressCallback& progress = {});

}  // namespace cmaps
