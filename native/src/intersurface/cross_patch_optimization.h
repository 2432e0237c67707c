// The patch-wise map's last stage: the partition's paths stop being walls.
// Until here A's vertices move inside their patch's canonical triangle and
// slide along paths (patch_map_optimization.h), so the paths where the two
// partitions were traced stay where they were traced, and whatever the
// traced paths got wrong (a patch corner's angle far wider on one mesh than
// on the other, a path hugging one side of a limb on A and the other on B)
// stays wrong. Schreiner et al. 2004 let vertices cross the paths while the
// map is refined; here A's embedding lives on the whole base mesh, glued
// into one flat surface with cone points (base_complex.h), and each vertex
// moves in the plane of its base triangle developed with its neighbours, into
// a neighbour when the move crosses a side, for a lower symmetric Dirichlet
// energy of both directions (chord_energy.h), the chords of input triangles
// cut by paths included (split_triangles.h). A vertex whose ring holds a
// folded chord steps first against the gradient of the folded area.
//
// Either side can move: below, A is the moving side and B the fixed one,
// both glued embeddings (glued_side.h), so after A's vertices crossed B can
// cross against A's embedding as it is then (Schreiner et al. refine both
// meshes): the fixed side of a map from its patch embeddings never moves,
// and its paths' shear (each path laid straight, turning on the surface)
// stays otherwise.
//
// Invariants: base vertices (the features) and hole fans stay where they
// are; a move keeps every triangle of the vertex's ring turning the same
// way as the whole embedding and holding no base vertex inside, and the
// ring's outline does not move, so A's embedding stays a bijection onto the
// base mesh and the map stays continuous and bijective. B's embedding is
// fixed; each of B's vertices keeps the triangle of A holding it (re-found
// among the ring's triangles when a ring moves), which gives the map back.
#pragma once
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

#include "intersurface/base_complex.h"
#include "intersurface/chord_energy.h"
#include "intersurface/glued_side.h"
#include "intersurface/map_gradient.h"
#include "intersurface/patch_locator.h"
#include "intersurface/split_triangles.h"

namespace cmaps {

struct CrossPatchOptimization {
  double energy_before = 0, energy_after = 0;  // area-weighted mean over A's triangles (both directions)
  int moves = 0, crossings = 0;                // moves kept; those into another base triangle
};

class CrossPatchMap {
 public:
  // A = partition.sides[moving], B = the other side, at their glued embeddings.
  CrossPatchMap(const ConsistentPartition& partition, int moving, GluedEmbedding a, GluedEmbedding b);
  // A = partition.sides[0] with its patch embeddings `uv_a`, B = sides[1]
  // with `uv_b`.
  CrossPatchMap(const ConsistentPartition& partition, const PatchParameterization& uv_a,
                const PatchParameterization& uv_b);

  // A's embedding as it is now (for B to move against next).
  const GluedEmbedding& moved() const { return a_glued_.embedding(); }

  // Sweeps over A's vertices (after the first, those whose ring changed)
  // until one moves nothing or `sweeps` are done. `keep_going(fraction
  // done)` is asked after each sweep; false throws Cancelled.
  // A sweep moves A's two halves (split across A's longest axis) side by
  // side on two of `threads`, each half's vertices whose moves read and
  // write nothing of the other's (moves_alone), then the others in order;
  // the halves are independent, so the map is the same for any `threads`.
  CrossPatchOptimization optimize(int sweeps, const std::function<bool(double)>& keep_going = {},
                                  int threads = 1);

  // The invariants, counted (both 0 unless broken): A's and B's triangles
  // that turn the wrong way in the plane of their corners (glued_side.h), and
  // B's vertices that lie outside the triangle of A said to hold them, by
  // more than 1e-9 of the canonical side (not in barycentric weight: a
  // vertex of B on a path has a point in each patch beside it, embedded
  // apart, which agree to rounding, and on a 100k-face mesh's tiny
  // triangles that rounding is over 1e-9 in weight). Holes' fans are left
  // out (their triangles, the centres of B's): they are no part of the
  // surfaces.
  int turned_triangles() const;
  int stray_hosts() const;

  // A's free vertex v tried at its point moved by `offset` in its ring's
  // plane, what each descent step weighs (for tests of its derivative):
  // the ring's energy, its folded chords' area, the mean distance from v to
  // its neighbours there and, with `gradient`, both derivatives by the
  // point. Nothing for fixed vertices or refused points.
  struct RingTrial {
    double energy = 0, folded = 0, length = 0;
    PointGradient gradient;
  };
  std::optional<RingTrial> ring_trial(int v, const Vec2& offset, bool gradient) const;

  // Per input vertex of A: its image on B's input triangles (features exact).
  std::vector<InputLocation> map_a(const TriangleMesh& b_input, int threads) const;
  // Per input vertex of B: its image on A's input triangles (features exact).
  std::vector<InputLocation> map_b(const TriangleMesh& a_input) const;
  // Per corner of A's and of B's input triangles: the image of the point of
  // the triangle next to the corner (corner_points), for per-corner values.
  std::vector<InputLocation> map_a_corners(const TriangleMesh& a_input, const TriangleMesh& b_input,
                                           int threads) const;
  std::vector<InputLocation> map_b_corners(const TriangleMesh& a_input, const TriangleMesh& b_input,
                                           int threads) const;

 private:
  struct Move;
  struct Ring;
  double total_energy() const;
  bool improve(int v);
  // Whether the side's triangle f turns the wrong way in its corners' plane
  // (turned_triangles counts them).
  bool turned(const GluedSide& side, int f) const;
  // Whether B's vertex w lies outside A's triangle `face`, developed into
  // that triangle's own plane (stray_hosts counts those of the hosts).
  bool strays(int w, int face) const;
  // Whether `move` of v would break an invariant as turned_triangles and
  // stray_hosts check it. A move's trial lays out v's ring in v's own
  // plane; near a base vertex (a cone point of the base mesh, where a point
  // has copies around it) other planes can disagree: a triangle at the base
  // vertex can turn in its other corners' planes, and a vertex of B the
  // ring's layout puts inside a triangle can lie outside it developed
  // around that triangle.
  bool breaks_invariants(int v, const Move& move);
  // Whether v, in `half` of A (per vertex of A: 0 or 1), moves reading and
  // writing only what moves of that half's vertices change: its ring's
  // triangles and its cut triangles have all corners in the half, and B's
  // vertices in its ring share B's triangles and cut triangles only with
  // vertices of B hosted in triangles of A whose corners are all in the
  // half. Moves keep B's vertices in the mover's ring, so a sweep of such
  // vertices of one half never touches what one of the other half reads.
  bool moves_alone(int v, const std::vector<char>& half) const;
  bool gather_ring(int v, Ring& ring) const;
  // v moved to q of its ring's plane: the move, with its energy (inf when
  // not allowed); with `gradient`, also the energy's derivative by q.
  Move trial(int v, const Vec2& q, const Ring& ring, PointGradient* gradient = nullptr) const;
  void apply(int v, const Move& move);
  // B's point (a base triangle and canonical point of B's embedding) on A,
  // among A's triangles around `near_face`: the triangle and weights.
  RefinedPoint locate_on_a(int patch, const Vec2& point, int near_face) const;
  // Canonical points (base triangle, point) located on B's input triangles.
  std::vector<InputLocation> located_on_b(const std::vector<std::pair<int, Vec2>>& points,
                                          const TriangleMesh& b_input, int threads) const;
  // A point of a side's refined mesh as a base triangle and canonical point.
  static std::pair<int, Vec2> canonical_point(const GluedSide& side, const RefinedPoint& p);
  // B's point (base triangle, canonical point) on B, trying B's triangle `hint` first.
  Image image_on_b(int home, const Vec2& point, int hint, int* face = nullptr) const;

  const PartitionSide& a_;
  const PartitionSide& b_;
  const std::vector<char> fan_;  // per base triangle: whether it is a hole's fan
  BaseComplex base_;
  GluedSide a_glued_, b_glued_;
  double scale_ = 1;        // B scaled to A's area
  double orientation_ = 1;  // how A's embedding turns in the canonical plane
  std::vector<char> fixed_; // per vertex of A: base vertices and hole fans
  std::vector<SourceTriangle> shape_a_, shape_b_;  // per triangle (zero for a hole's fan)
  SplitTriangles split_a_, split_b_;               // input triangles cut by paths, charged by their chords too
  std::vector<Image> image_;               // per vertex of A: its image on B
  std::vector<int> image_face_;            // per vertex of A: B's triangle holding its image
  std::vector<PatchLocator> locate_b_;     // per base triangle: B's triangles reaching into it
  std::vector<RefinedPoint> host_;          // per vertex of B: the triangle of A holding it
  std::vector<Image> back_image_;           // per vertex of B: its image on A
  std::vector<std::vector<int>> hosted_;    // per triangle of A: the vertices of B in it
};

}  // namespace cmaps
