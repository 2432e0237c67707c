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
  // Meshes with holes (thesis 3.5): each hole was closed by a temporary
  // centre vertex and a fan of triangles, left out of the results above.
  // They are kept here so that the sphere can be covered when needed (e.g.
  // to resample): centre h is vertex n + steiner.size() + h of
  // hole_triangles (n = input vertices), whose other corners index like
  // `triangles`.
  int holes = 0;
  std::vector<Triangle> hole_triangles;
  std::vector<Vec3> hole_centres_sphere;
  std::vector<Vec3> hole_centres_position;    // the loop's centroid, input coordinates
  std::vector<std::vector<int>> hole_features;  // per hole: indices into the features, along the boundary
};

// `features` are distinct vertex indices (at least 3). The mesh may have
// holes (boundary loops; thesis 3.5) when it is genus 0 once they are
// closed: each hole must be ringed by at least 3 features on its boundary;
// the boundary between two consecutive ones maps onto the great-circle arc
// between their targets, and the hole maps to the spherical polygon of its
// features' targets (which must run around it in the boundary's order and
// enclose no other target). `targets` holds one
// direction per feature (normalized here; they must be distinct), or is empty
// to take them from the unconstrained parameterization. Throws InvalidInput /
// TopologyError for bad input and Cancelled when `progress` says so.
ConstrainedResult constrained_spherical_parameterization(const TriangleMesh& mesh, const std::vector<int>& features,
                                                         const std::vector<Vec3>& targets,
                                                         const SphereOptions& options = {},
                                                         const ProgressCallback& progress = {});

}  // namespace cmaps
