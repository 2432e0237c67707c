// Lowers the distortion of the bijection between two surfaces that their
// spherical parameterizations define (a point of A goes to the point of B
// with the same sphere point) by moving the sphere points of A's vertices,
// then of B's, and so on: each move slides a vertex's image over the other
// surface.
//
// The energy is symmetric: the symmetric Dirichlet energy of every triangle
// of A against the triangle its corners' images on B form, plus the same for
// B's triangles on A (each direction averaged over its surface's area, the
// other surface scaled to the same area), as measure_intersurface_map
// measures them. Moving a vertex of A changes its own image and the images
// on A of B's vertices inside its spherical star, and both terms see that.
//
// Invariants: a vertex never leaves the kernel of its spherical star, so both
// spherical triangulations stay embeddings and the map stays a bijection (and
// the union of a star never changes, so the other side's vertices inside it
// stay inside it); fixed vertices (features) never move; and since the energy
// does not see the sphere, no spherical triangle may become thinner than 1e-3
// (det over squared edges) or half its starting value, whichever is lower.
// Each move is one Newton step on the tangent plane (gradient and Hessian by
// central differences: images move piecewise linearly) with a backtracking
// line search.
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/sphere_locator.h"

namespace cmaps {

struct MapSide {
  const TriangleMesh& surface;  // triangulated like its spherical map (refined, Steiner vertices included)
  std::vector<Vec3>& sphere;    // one unit vector per vertex of `surface`, moved in place
  std::vector<char> fixed;      // per vertex: never moves
};

class MapOptimizer {
 public:
  MapOptimizer(MapSide a, MapSide b, int threads);
  ~MapOptimizer();

  // `rounds` times: A's vertices, then B's, each in coloured parallel sweeps
  // until no vertex moves more than `tolerance` (relative to its star) or
  // `sweeps`. `keep_going` is asked between sweeps; false stops early.
  void optimize(int rounds, int sweeps, double tolerance, const std::function<bool(double)>& keep_going);

 private:
  struct Side;
  void refresh(Side& moving, Side& other);
  double move(Side& moving, Side& other, int v) const;
  std::unique_ptr<Side> a_, b_;
  std::unique_ptr<SphereLocator> on_other_;  // during a pass: locates on the side that stays put
  int threads_;
};

}  // namespace cmaps
