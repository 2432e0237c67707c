// Topological and geometric validation of a triangle mesh.
#pragma once
#include <string>

#include "consistent_maps/mesh.h"

namespace cmaps {

struct MeshReport {
  int vertices = 0;             // entries in the vertex array
  int referenced_vertices = 0;  // vertices used by at least one triangle
  int faces = 0;
  int components = 0;  // components of the triangles joined through shared vertices
  int boundary_loops = 0;
  int euler_characteristic = 0;  // V - E + F over referenced vertices
  int genus = -1;                // -1 when undefined (non-manifold or several components)
  int non_manifold_edges = 0;    // edges with more than two incident triangles
  int non_manifold_vertices = 0; // vertices whose triangle fan is not one disk/half-disk
  int degenerate_faces = 0;      // repeated vertex index or zero area
  int duplicate_faces = 0;       // same vertex set as an earlier face
  int inconsistently_oriented_edges = 0;  // interior edges traversed twice in one direction
  int non_finite_vertices = 0;
  int out_of_range_indices = 0;

  bool manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
  bool closed() const { return boundary_loops == 0; }
};

MeshReport check_mesh(const TriangleMesh& mesh);

// Volume enclosed by a closed mesh: negative when its triangles face inwards.
double signed_volume(const TriangleMesh& mesh);

// Sum of the triangles' areas.
double surface_area(const TriangleMesh& mesh);

// One line describing the report (for CLI output and error messages).
std::string summarize(const MeshReport& report);

// Throws InvalidInput / TopologyError naming the first defect unless the mesh
// is one closed, manifold, consistently oriented genus-0 triangle mesh with
// finite coordinates, e.g. "mesh has genus 2 (closed, 1 component);
// spherical parameterization needs genus 0". Zero-area triangles are allowed.
// With `allow_holes`, boundary loops are accepted (a genus-0 surface with
// holes, as constrained and consistent parameterization take them).
void require_sphere_topology(const TriangleMesh& mesh, bool allow_holes = false);

// The same for an inter-surface map (with a partner of the same genus and as
// many holes): one manifold, consistently oriented surface of finite
// coordinates, closed or with holes, of any genus, e.g. "mesh has 2
// components; an inter-surface map needs one connected surface". Vertices no
// triangle uses are allowed: the map leaves them out. Returns the mesh's report.
MeshReport require_pair_map_topology(const TriangleMesh& mesh);

}  // namespace cmaps
