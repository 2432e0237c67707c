// One patch of a patch-wise inter-surface map, both directions, as a
// function of one free source vertex's canonical point: the source's
// triangles mapped onto the target and the target's triangles mapped back
// (chord_energy.h), what the in-patch optimizer (patch_map_optimization.h)
// lowers one vertex at a time.
//
// Invariants: every source triangle of the patch turns the way the whole
// embedding turns (a trial that would turn one is refused), so the
// embedding stays a bijection onto the canonical triangle; each target
// vertex of the patch is held by the source triangle containing its
// canonical point, and moving a vertex re-maps only those held in its ring
// (the ring's outline stays). Vertices and triangles are numbered locally,
// in the order of their indices in the meshes.
#pragma once
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "intersurface/chord_energy.h"
#include "intersurface/map_gradient.h"
#include "intersurface/patch_locator.h"

namespace cmaps {

class PatchEnergy {
 public:
  // The source's patch (its triangles `faces`, embedded by `uv`, which the
  // moves keep up to date) and the target's (`target_faces`, `target_uv`),
  // the target scaled by `scale` to the source's area.
  PatchEnergy(const PartitionSide& source, std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces,
              const PartitionSide& target, const std::unordered_map<int, Vec2>& target_uv,
              const std::vector<int>& target_faces, double scale);

  // Both directions' energies, the target's weighted to the source's area;
  // `area` gets the source area they cover.
  double total(double& area) const;

  // Whether mesh vertex v may move: not when its ring here holds too many target vertices to re-map.
  bool movable(int v) const;

  // What the trials of one vertex share: the local target vertices inside
  // its ring (sorted) and their triangles (sorted), whose images move with
  // it, and the mean distance from it to its ring's other corners.
  struct Hosted {
    std::vector<int> vertices, triangles;
    std::vector<std::array<int, 3>> slots;  // per triangle: each corner's index in `vertices`, -1 if not there
    double length = 0;
  };
  Hosted hosted(int v) const;

  // Vertex v at canonical point p: its image, the re-mapped target vertices, the ring's energy.
  struct Remap {
    Image image;  // the target vertex's new image
    int host;     // its new source triangle (local)
    Jacobian jacobian = Jacobian::Zero();  // the image's derivative by v's point (when a gradient is asked for)
  };
  struct Move {
    Vec2 point;
    Image image;
    int image_face = -1;  // the target's triangle holding the image
    std::vector<std::pair<int, Remap>> remapped;  // per local target vertex, in Hosted::vertices' order
    double energy = kChordInf;
  };

  // The energy of mesh vertex v's triangles in this patch and of the
  // target's triangles around the target vertices they hold (`inside`,
  // from hosted(v)), with v at p; inf when one of v's triangles would turn
  // over. With `gradient`, also its derivative by p.
  Move trial(int v, const Vec2& p, const Hosted& inside, PointGradient* gradient = nullptr) const;

  // One descent step of mesh vertex v, if this sweep tries it (descent_step.h).
  bool improve(int v);

  // Starts a sweep: the vertices to try are those whose ring changed since the last.
  void begin_sweep();

  void apply(int v, const Move& m);

  // The source's patch embedded anew: every point read again from the uv
  // map, images and hosts located again (what a new PatchEnergy would hold;
  // the triangles' shapes and the target's side are kept).
  void reembed();

  const std::unordered_map<int, Vec2>& uv() const { return uv_; }

  // Per source vertex: how much the map scales area around it, the
  // area-weighted geometric mean over its triangles of image area (chord
  // triangle, target scaled) over source area; 1 where it has no area.
  std::unordered_map<int, double> area_ratios() const;

 private:
  // Local triangle f's energy, local vertex i's image replaced by q (none
  // when i < 0); with `gradient`, its derivative added, q moving by `moved`.
  double source_energy(int f, int i, const Image* q, const Jacobian* moved = nullptr,
                       PointGradient* gradient = nullptr) const;
  // Local target triangle g's energy with the re-mapped images (`slots`:
  // its corners' indices in `remapped`, as Hosted::slots); with `gradient`, its
  // derivative (weighted as the trial weighs it) added.
  double target_energy(int g, const std::array<int, 3>& slots, const std::vector<std::pair<int, Remap>>& remapped,
                       PointGradient* gradient = nullptr) const;
  double signed_area(int f, int i, const Vec2& p) const;

  const PartitionSide& source_;
  std::unordered_map<int, Vec2>& uv_;  // kept up to date for the path slides
  const PartitionSide& target_;
  double scale_;
  double orientation_ = 1;
  // The source's side of the patch, local: vertices, their mesh index, canonical point and image.
  std::vector<int> vertex_;
  std::unordered_map<int, int> local_;
  std::vector<Vec2> point_;
  std::vector<Image> image_;
  std::vector<int> image_face_;  // per vertex: the target's triangle holding its image
  std::vector<int> face_;                     // per local triangle: its index in the mesh
  std::vector<std::array<int, 3>> triangle_;  // and its local corners
  std::unordered_map<int, int> local_face_;   // per mesh triangle of the patch: its local index
  std::vector<SourceTriangle> shape_;
  std::vector<std::vector<int>> ring_;  // per local vertex: its local triangles
  std::vector<std::vector<int>> host_;  // per local triangle: the local target vertices inside it
  std::vector<char> active_, changed_;  // per local vertex: to try in this sweep, in the next
  // The target's side, local.
  std::vector<Vec2> target_point_;
  std::vector<Image> back_image_;
  std::vector<std::array<int, 3>> back_triangle_;
  std::vector<SourceTriangle> back_shape_;
  std::vector<std::vector<int>> target_ring_;  // per local target vertex: its local target triangles
  std::unique_ptr<PatchLocator> target_locator_;
};

}  // namespace cmaps
