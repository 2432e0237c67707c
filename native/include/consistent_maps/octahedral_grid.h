// Praun & Hoppe's flat octahedron: the regular sphere grid behind remeshes
// and geometry images. An (n+1) x (n+1) image, pixel (i, j) at
// a = j - n/2, b = i - n/2; its inner diamond |a| + |b| <= n/2 is the upper
// hemisphere (octahedron point (a, b, n/2 - |a| - |b|)), the four corner
// triangles fold onto the lower faces (point (sgn a (n/2 - |b|),
// sgn b (n/2 - |a|), n/2 - |a| - |b|)). Boundary pixels mirrored across an
// image edge's midpoint, and all four corners, are the same sphere point.
// Sphere positions are the octahedron points normalized.
#pragma once
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

struct OctahedralGrid {
  int n = 0;                       // image is (n+1) x (n+1) pixels
  std::vector<Vec3> sphere;        // n^2 + 2 unique unit vectors
  std::vector<Triangle> triangles; // 2 n^2, counter-clockwise seen from outside, each on one octahedron face
  std::vector<int> pixel_vertex;   // row-major (n+1)^2: vertex of pixel (i, j) at i * (n+1) + j

  int vertex(int i, int j) const { return pixel_vertex[static_cast<size_t>(i) * (n + 1) + j]; }
};

// Throws InvalidInput unless n is even and >= 2.
OctahedralGrid octahedral_grid(int n);

}  // namespace cmaps
