// Moves vertices of a spherical embedding to lower the stretch energy, one
// vertex at a time, never leaving the kernel of its star: each move is a
// Newton step on the tangent plane (Hessian by differences of the analytic
// gradient) with a backtracking line search that rejects any position where
// one of the vertex's triangles would flip. Moving only non-adjacent vertices
// at once keeps this invariant under parallel sweeps.
#pragma once
#include <vector>

#include "consistent_maps/progressive_mesh.h"
#include "sphere/correspondence_term.h"
#include "sphere/sphere_refinement.h"
#include "sphere/stretch_energy.h"

namespace cmaps {

class VertexOptimizer {
 public:
  // `weights` is indexed like mesh.triangles(); `sphere` holds one unit
  // vector per vertex (only active vertices are read or written).
  VertexOptimizer(const MeshRefinement& mesh, const std::vector<FaceWeights>& weights,
                  std::vector<Vec3>& sphere, int threads);

  // Up to `iterations` Newton steps on vertex v; returns the distance moved
  // relative to the shortest chord to a neighbour.
  double optimize_vertex(int v, int iterations);

  // Sweeps over all active vertices, graph-coloured so each colour class
  // runs in parallel, revisiting only the neighbourhoods of vertices that
  // moved more than `tolerance` (relative), for at most `max_sweeps` sweeps.
  void optimize_all(int max_sweeps, double tolerance);

  // The energy of the vertex's star with v at p (+inf if p leaves the kernel).
  double star_energy(int v, const Vec3& p, Vec3* gradient) const;

  // The total stretch energy of the active triangles.
  double total_energy() const;

  // Vertices that must not move (features), indexed by vertex; may be empty.
  void set_fixed(std::vector<char> fixed) { fixed_ = std::move(fixed); }

  // Vertices restricted to great-circle arcs (may be null); must outlive the optimizer.
  void set_arcs(const ArcChains* arcs) { arcs_ = arcs; }

  // A consistency term added to the stretch energy (may be null; its
  // gradient is taken by central differences); must outlive the optimizer.
  void set_correspondence(CorrespondenceTerm* term) { term_ = term; }

 private:
  const MeshRefinement& mesh_;
  const std::vector<FaceWeights>& weights_;
  std::vector<Vec3>& sphere_;
  std::vector<char> fixed_;
  const ArcChains* arcs_ = nullptr;
  CorrespondenceTerm* term_ = nullptr;
  int threads_;

  double optimize_on_arc(int v, int iterations);
  Vec3 correspondence_gradient(int v, const Vec3& p) const;
};

}  // namespace cmaps
