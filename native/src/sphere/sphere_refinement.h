// The coarse-to-fine stage shared by every spherical parameterization:
// replay a progressive mesh's vertex splits on the sphere, placing each new
// vertex inside its 1-ring kernel and optimizing it and its neighbours, with
// global optimization passes as the mesh grows and at the end.
#pragma once
#include <utility>
#include <vector>

#include "consistent_maps/progress.h"
#include "consistent_maps/progressive_mesh.h"
#include "consistent_maps/spherical_parameterization.h"
#include "sphere/correspondence_term.h"

namespace cmaps {

// Same shape centred at the area centroid and scaled to total area 4 pi, so
// energies and tolerances do not depend on the input's position or scale.
std::vector<Vec3> normalized_positions(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles);

// `sphere` holds valid positions for the base vertices of `pm` on entry (the
// base triangles positively oriented) and every vertex's position on exit.
// `geometries` are the surfaces whose summed stretch is minimized (one per
// shape sharing the connectivity); `fixed` vertices (may be empty) never move.
// Progress is reported through `progress` as "refine" then "optimize".
// `extras` (optional) adds the constraints of meshes with holes.
struct RefineExtras;
void refine_on_sphere(const ProgressiveMesh& pm, const std::vector<const std::vector<Vec3>*>& geometries,
                      const std::vector<char>& fixed, const SphereOptions& options, std::vector<Vec3>& sphere,
                      const ProgressSlice& progress, const RefineExtras* extras = nullptr);

// Vertices that move only along great-circle arcs (thesis 3.5, constrained
// paths): each chain runs between two fixed vertices, and the great-circle
// arc between those holds the whole chain; an interior chain vertex is
// placed and moved only on that arc, between its current (active) chain
// neighbours.
struct ArcChains {
  std::vector<std::vector<int>> chains;
  std::vector<int> chain_of, index_in_chain;  // per vertex; -1 = not an interior chain vertex
  // Fills chain_of and index_in_chain from chains.
  void index(int vertex_count);
  bool constrained(int v) const { return !chain_of.empty() && chain_of[v] >= 0; }
  // The nearest active chain vertices before and after v (its current path neighbours).
  std::pair<int, int> neighbours(const MeshRefinement& mesh, int v) const;
  // The chain's great circle: p(t) = cos t * origin + sin t * axis, t in [0, end].
  void frame(const std::vector<Vec3>& sphere, int chain, Vec3& origin, Vec3& axis) const;
};

struct RefineExtras {
  std::vector<char> stretch_free_faces;  // per face: weights are the regularizer alone
  ArcChains arcs;
  ReferenceMap reference;  // with a surface: consistency with its map joins the energy (geometries[0] is measured)
};

}  // namespace cmaps
