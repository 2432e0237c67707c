// Keeps B's half of a corresponding path near where A's half lies. Paths on
// B are traced through the sectors A's path used at its ends, but the
// shortest such path on B can still pass a handle on the other side than on
// A, and cycles found on each mesh alone can belong to different handles or
// wind differently: the patches then twist against each other. B is brought
// into A's frame by a transform fitted to the given feature pairs (affine
// from 4 pairs unless it stretches more than 4:1 or mirrors, else a
// similarity from 3, else the centroids and areas, B turned onto A's
// principal axes when that matches clearly closer), then refined by
// iterative closest points between the two surfaces, and a step of B's
// search costs more the farther it lies from A's path there:
// 1 + kPull * distance / sqrt(A's area), and 1 on A's path itself, so that
// a copy of A gets A's own paths. A torus against a stretched copy of
// itself, over 21 sets of 0-16 true pairs: 12.1 -> 2.3 % mean error
// (BENCHMARKS.md).
#pragma once
#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

class PathGuide {
 public:
  // Positions of the given pairs on A and on B (any count), the meshes for
  // the fallback (with fewer than 3 pairs B may be turned onto A's principal
  // axes: a kitten and its stretched copy stood up from y-up to z-up, no
  // pairs, 15.8 -> 2.1 % mean error).
  PathGuide(const std::vector<Vec3>& on_a, const std::vector<Vec3>& on_b, const TriangleMesh& a,
            const TriangleMesh& b);

  Vec3 to_a(const Vec3& on_b) const { return transform_ * on_b; }

  // The step factor for B's search near the polyline `a_path` (A positions).
  // It remembers where its last point lay, so one thread calls it at a time.
  std::function<double(const Vec3&)> near(const std::vector<Vec3>& a_path) const;

  // Index of the point of `b_points` whose image in A's frame is nearest `a_point`.
  int nearest(const Vec3& a_point, const std::vector<Vec3>& b_points) const;

 private:
  // Iterative closest points both ways (vertex samples of each mesh matched
  // to the other's nearest in A's frame), the pairs weighing as much as all
  // samples, refitted affinely while the matched distance falls: meshes posed
  // alike line up even when the pairs are few, coplanar or absent.
  // Returns the summed squared distances of the matches at the fit kept.
  double align_surfaces(const std::vector<Vec3>& on_a, const std::vector<Vec3>& on_b, const TriangleMesh& a,
                      const TriangleMesh& b);

  Eigen::Affine3d transform_ = Eigen::Affine3d::Identity();
  double scale_a_ = 1;
};

}  // namespace cmaps
