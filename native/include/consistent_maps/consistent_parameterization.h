// Consistent spherical parameterization of a set of genus-0 meshes
// (thesis 3.2): corresponding features of all members land on one common
// point of the sphere each, and those points are chosen to suit every shape.
//
//   1. unconstrained map of one member -> initial feature locations;
//   2. constrained map of every other member to them;
//   3. remesh every member on one octahedral grid, features snapped to samples;
//   4. one mesh, the grid, carrying all n remeshed shapes;
//   5. its unconstrained map, stretch and quadric summed over the shapes,
//      gives feature locations that respect every shape;
//   6. constrained map of every member to those locations, its paths laid
//      out along its previous map carried through the map of step 5 (or
//      along its own unconstrained map when that is more efficient).
// Steps 3-6 run twice, the second time remeshing along the maps of the
// first; the maps before the last round are quick ones (effort 0).
#pragma once
#include <vector>

#include "consistent_maps/constrained_parameterization.h"
#include "consistent_maps/mesh.h"
#include "consistent_maps/progress.h"

namespace cmaps {

struct ConsistentMember {
  TriangleMesh mesh;
  std::vector<int> features;  // per feature: this member's vertex, or -1 where it lacks the feature
};

struct ConsistentOptions {
  SphereOptions sphere;
  int first = -1;  // member seeding step 1; -1 = the first member that has every feature
  int grid = 64;   // octahedral grid resolution of the intermediate remeshes (steps 3-5)
  // Steps 3-6 twice, the paths of step 6 laid out along carried maps (see
  // above); false: steps 3-6 once, each member's paths along its own
  // unconstrained map (what a pair's inter-surface map starts from: its
  // distortion optimization was measured from those maps).
  bool carry_guides = true;
  // Steps 1-6 this many times, restart k with seed + k, keeping the run whose
  // maps suit the members best (ConsistentResult::suitability). With few
  // features a run can wind some member's map the wrong way around them
  // (sets/cactus, 8 features, seeds 1-7: 2.7-6.0 % ground-truth error, the
  // bad runs 76-89 % of a member's own efficiency where the good ones keep
  // 96-99 %).
  int restarts = 1;
  // Step 7 (see consistent/member_alignment.h): each member's map refitted
  // towards the seeding member's, kept where the map between them distorts
  // less, as long as the member keeps 85 % of its own map's efficiency.
  // Lowers the ground-truth error on poses of one shape (sets/cactus, 8
  // features: mean 3.1 -> 1.6 %, worst pose 3.6 -> 1.99 %) at some of each
  // member's own efficiency (worst 97 -> 86 % of its own map's).
  bool align = false;
};

struct ConsistentResult {
  std::vector<Vec3> feature_locations;  // per feature: the common unit vector (step 5)
  std::vector<Vec3> initial_locations;  // per feature: from the first member alone (step 1)
  std::vector<ConstrainedResult> members;  // final maps (step 6), in member order
  int first = 0;
  double seconds = 0;
  // The mean over members of their final efficiency over their own quick
  // unconstrained map's (0 when not measured: one run without carried guides);
  // per restart, and the restart kept. Both measure the runs' maps before
  // step 7 (align), which trades some efficiency for correspondence.
  double suitability = 0;
  std::vector<double> restart_suitability;
  int restart = 0;
};

// Members may have holes (thesis 3.5) when the same features (at least 3)
// ring corresponding holes on every member; InvalidInput otherwise.
// Throws InvalidInput when feature lists differ in length, name a vertex out
// of range, leave a member with fewer than 3 features, or no member has every
// feature; TopologyError for a member that is not closed genus 0.
ConsistentResult consistent_spherical_parameterization(const std::vector<ConsistentMember>& members,
                                                       const ConsistentOptions& options = {},
                                                       const ProgressCallback& progress = {});

// Adds a member to an existing set later (thesis 4.2): its constrained map to
// the set's feature locations; features it lacks (-1) are left free.
ConstrainedResult parameterize_to_locations(const ConsistentMember& member, const std::vector<Vec3>& locations,
                                            const SphereOptions& options = {},
                                            const ProgressCallback& progress = {});

// A member's map as a plain parameterized surface: the refined triangulation
// (input vertices, then Steiner vertices at their surface positions) and one
// unit vector per vertex. With `close_holes`, a mesh with holes also gets
// their temporary centres (after the Steiner vertices) and fan triangles
// (after the others), so that it covers the whole sphere.
struct ParameterizedSurface {
  TriangleMesh surface;
  std::vector<Vec3> sphere;
};
ParameterizedSurface parameterized_surface(const TriangleMesh& mesh, const ConstrainedResult& map,
                                          bool close_holes = false);

// Consistent remeshes: every member sampled at the same sphere points, so
// they share one connectivity; feature k sits at vertex feature_vertices[k].
struct ConsistentRemesh {
  std::vector<Vec3> sphere;                 // the sample points
  std::vector<Triangle> triangles;          // their connectivity
  std::vector<std::vector<Vec3>> positions; // per member: one position per sample
  std::vector<int> feature_vertices;        // per feature
  // Meshes with holes: per sample, whether it falls in a hole of some
  // member (its positions there interpolate the hole's temporary fan);
  // grid triangles with such a corner are left out of `triangles`, so the
  // remeshes share one connectivity with the holes open (samples are kept,
  // unreferenced, so sample indices match the grid).
  std::vector<char> in_hole;
};
// On the octahedral grid of resolution n (even, >= 2).
ConsistentRemesh consistent_remesh(const std::vector<ConsistentMember>& members, const ConsistentResult& result,
                                   int n, int threads = 2);

}  // namespace cmaps
