// Meshes with holes (thesis 3.5): every boundary loop is closed by a
// temporary centre vertex joined to the loop by a fan of triangles, so the
// closed-mesh machinery applies; the fan's region on the sphere is where the
// hole maps, and it is removed from the results again.
#pragma once
#include <string>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

struct ClosedMesh {
  TriangleMesh mesh;   // input vertices then one centre per hole; input triangles then the fans
  int input_vertices = 0, input_triangles = 0;
  // Per hole: its boundary vertices in the order the fan triangles
  // (centre, loop[j], loop[j + 1]) run, starting at the loop's smallest index.
  std::vector<std::vector<int>> loops;
  int centre(int hole) const { return input_vertices + hole; }
};

// The mesh itself when it is closed; otherwise every boundary loop fanned to
// a centre at the loop's centroid. Throws TopologyError when the mesh (open
// or not) is not a manifold, consistently oriented genus-0 surface with holes
// (with `any_genus`, of any genus: inter-surface maps of genus >= 1).
ClosedMesh close_holes(const TriangleMesh& mesh, bool any_genus = false);

// Per hole: the indices into `features` of the features on its loop, in
// loop order. Throws InvalidInput when a hole has fewer than 3 of them; the
// message starts with `who` (e.g. "mesh 2: ").
std::vector<std::vector<int>> hole_features(const ClosedMesh& closed, const std::vector<int>& features,
                                            const std::string& who = "");

}  // namespace cmaps
