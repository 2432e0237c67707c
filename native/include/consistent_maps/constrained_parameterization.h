// Constrained spherical parameterization (thesis 3.3): a bijective,
// stretch-minimizing map of a closed genus-0 mesh onto the sphere with every
// feature vertex exactly at its target point.
//
// The targets are triangulated on the sphere; a network of non-crossing mesh
// paths with the same topology is traced between the features (inserting
// Steiner vertices where no path exists along mesh edges); the mesh is
// simplified down to the features while path vertices collapse only along
// their paths, so the base mesh is the targets' triangulation; refinement on
// the sphere then proceeds as in the unconstrained case with features fixed.
#pragma once
#include <array>
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/progress.h"
#include "consistent_maps/spherical_parameterization.h"

namespace cmaps {

// A vertex inserted on the input surface: a convex combination of at most
// three input vertices (weights sum to 1; unused slots have vertex -1).
struct SteinerVertex {
  std::array<int, 3> vertices{-1, -1, -1};
  std::array<double, 3> weights{0, 0, 0};
  Vec3 sphere = Vec3::Zero();
};

struct ConstrainedResult {
  std::vector<Vec3> sphere;              // one unit vector per input vertex, input order
  std::vector<SteinerVertex> steiner;    // vertex n + i of `triangles` is steiner[i]
  std::vector<Triangle> triangles;       // the refined triangulation the map is piecewise linear on
  std::vector<int> input_triangle;       // per refined triangle: the input triangle it lies in
  std::vector<Vec3> targets;             // per feature (given, normalized, or automatic)
  SphericalMapReport report;             // measured on the refined triangulation
  double max_constraint_error = 0;       // max |sphere[feature] - target|
  int auxiliary_vertices = 0;            // free base vertices added so the base encloses the centre
  int retraced_paths = 0;
  int layout_flips = 0;                  // arcs flipped to shorter surface paths
  double seconds_paths = 0, seconds_simplify = 0, seconds_optimize = 0;
};

// `features` are distinct vertex indices (at least 3). `targets` holds one
// direction per feature (normalized here; they must be distinct), or is empty
// to take them from the unconstrained parameterization. Throws InvalidInput /
// TopologyError for bad input and Cancelled when `progress` says so.
ConstrainedResult constrained_spherical_parameterization(const TriangleMesh& mesh, const std::vector<int>& features,
                                                         const std::vector<Vec3>& targets,
                                                         const SphereOptions& options = {},
                                                         const ProgressCallback& progress = {});

}  // namespace cmaps
