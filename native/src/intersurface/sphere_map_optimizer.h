// Lowers the distortion of the bijection between two surfaces that their
// spherical parameterizations define (a point of A goes to the point of B
// with the same sphere point) by moving the sphere points of A's vertices,
// then of B's, and so on: each move slides vertex images over the other
// surface.
//
// The energy is symmetric: the symmetric Dirichlet energy of every sampled
// triangle of A (the input's) against the triangle its corners' images on B
// form, plus the same for B's on A (each direction averaged over its
// surface's area, the other surface scaled to the same area), exactly what
// measure_intersurface_map measures, plus a charge for each folded image
// triangle (sphere_map_side.h). Moving a vertex of A changes its own
// image and the images on A of B's vertices inside its spherical star, and
// both terms see that.
//
// Two kinds of moves. A vertex move slides one vertex (one Newton step on the
// tangent plane, gradient and Hessian by central differences: images move
// piecewise linearly, with a backtracking line search). A region move
// (sphere_region_moves.cpp) deforms a whole spherical cap smoothly: it
// carries a part of the surface (a cow's tail, a leg) whose image is too
// small or too large as one piece, which vertex moves, each held by its
// neighbours, cannot do.
//
// Invariants: both spherical triangulations stay embeddings (a vertex move
// never leaves the kernel of the vertex's star; a region move keeps every
// triangle it touches positively oriented, and the union of those triangles
// is fixed by its rim), so the map stays a bijection and the other side's
// vertices inside a star or region stay inside it; fixed vertices (features)
// never move; and since the energy does not see the sphere, no spherical
// triangle may become thinner than 1e-3 (det over squared edges) or half its
// starting value, whichever is lower.
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "consistent_maps/mesh.h"
#include "consistent_maps/sphere_locator.h"

namespace cmaps {

struct MapSide {
  const TriangleMesh& surface;  // triangulated like its spherical map (refined, Steiner vertices included)
  // The triangles the energy samples: the input's, over `surface`'s first
  // vertices (Steiner vertices and hole fans carry no energy of their own).
  const std::vector<Triangle>& sampled;
  std::vector<Vec3>& sphere;  // one unit vector per vertex of `surface`, moved in place
  std::vector<char> fixed;    // per vertex: never moves
  // Fixed vertices the region moves centre caps on (the features), so that
  // what is squeezed or spread around one can be scaled about it.
  std::vector<int> centres = {};
};

class MapOptimizer {
 public:
  MapOptimizer(MapSide a, MapSide b, int threads);
  ~MapOptimizer();

  // `rounds` times: A's vertices, then B's, each in coloured parallel sweeps
  // until no vertex moves more than `tolerance` (relative to its star) or
  // `sweeps`; with_regions, the first round's sweeps of each side follow
  // region moves from coarse to fine. `keep_going` is asked between sweeps
  // and every 256 evenly spread caps or each centred cap; false stops early.
  void optimize(int rounds, int sweeps, double tolerance, bool with_regions,
                const std::function<bool(double)>& keep_going);

 private:
  struct Side;
  void refresh(Side& moving, Side& other);
  double move(Side& moving, Side& other, int v) const;
  bool regions(Side& moving, Side& other, const std::function<bool()>& keep_going) const;
  double region_move(Side& moving, Side& other, const Vec3& centre, double radius, bool scale_only) const;
  std::unique_ptr<Side> a_, b_;
  std::unique_ptr<SphereLocator> on_other_;  // during a pass: locates on the side that stays put
  int threads_;
};

}  // namespace cmaps
