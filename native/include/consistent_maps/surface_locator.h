// Closest-point queries on a triangle mesh: for a point of space, the point
// of the surface nearest to it, as a triangle and barycentric coordinates
// (which interpolate anything stored per vertex or per corner there). Used
// where a map is known at vertices only and a point between their images
// has to be put back onto the surface (a pair's normal-map bake).
//
// A bounding-volume hierarchy of the triangles (median splits of the
// centroids along the box's longest axis) is searched nearer child first and
// pruned by the nearest distance found so far.
#pragma once
#include <array>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

struct SurfaceLocation {
  int triangle = -1;
  std::array<double, 3> barycentric{0, 0, 0};  // each >= 0, sum 1, in the triangle's corner order
  double distance = 0;                          // from the query point
};

class SurfaceLocator {
 public:
  // Any triangle soup (zero-area triangles allowed: they are searched along
  // their edges). Throws InvalidInput for no triangles, out-of-range indices
  // or non-finite coordinates.
  SurfaceLocator(std::vector<Vec3> vertices, std::vector<Triangle> triangles);

  // The nearest point of the surface; ties go to any of the triangles. Throws
  // InvalidInput for a non-finite point.
  SurfaceLocation locate(const Vec3& point) const;
  std::vector<SurfaceLocation> locate_all(const std::vector<Vec3>& points, int threads = 2) const;

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }

 private:
  struct Node {
    Vec3 low, high;
    int first = 0, count = 0;  // a leaf's triangles: order_[first, first + count)
    int children[2] = {-1, -1};
  };
  int build(int first, int count, std::vector<Vec3>& centroids);

  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<int> order_;  // triangle indices, each leaf's contiguous
  std::vector<Node> nodes_;  // nodes_[0] is the root
};

}  // namespace cmaps
