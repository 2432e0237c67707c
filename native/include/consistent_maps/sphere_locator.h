// Point location on a spherical parameterization: which chordal triangle's
// cone contains a direction, and the barycentric coordinates of the ray's
// intersection with that triangle's plane. Radial projection of the chordal
// triangles is how the piecewise-linear map sphere -> surface is defined, so
// these coordinates interpolate anything stored per vertex (positions,
// normals, UVs, colours) at any point of the sphere.
//
// A cube map of cells, each listing the triangles whose cone overlaps it
// (largest overlap first), answers a query with one or two sign tests:
// millions of queries per second per core.
#pragma once
#include <Eigen/Core>
#include <array>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct SphereLocation {
  int triangle = -1;
  std::array<double, 3> barycentric{0, 0, 0};  // each >= 0, sum 1, in the triangle's corner order
};

class SphereLocator {
 public:
  // `sphere` holds one unit vector per vertex; every chordal triangle must be
  // positively oriented (det(a, b, c) >= 0, zero-area ones are never
  // returned) and together they must cover the sphere once. Throws
  // InvalidInput for out-of-range indices, non-unit vectors or flipped triangles.
  SphereLocator(std::vector<Vec3> sphere, std::vector<Triangle> triangles);

  // Never fails for a non-zero finite direction (it need not be unit): a
  // direction on an edge or vertex gets any of the triangles around it.
  // Throws InvalidInput for a zero or non-finite direction.
  SphereLocation locate(const Vec3& direction) const;
  std::vector<SphereLocation> locate_all(const std::vector<Vec3>& directions, int threads = 2) const;

  // Barycentric interpolation of per-vertex values at the located points:
  // row k of the result is sum_i barycentric_i * values.row(corner_i).
  RowMatrixXd interpolate(const RowMatrixXd& values, const std::vector<SphereLocation>& at,
                          int threads = 2) const;
  // `values` holds `stride` doubles per vertex; returns `stride` per location.
  std::vector<double> interpolate(const std::vector<double>& values, int stride,
                                  const std::vector<SphereLocation>& at, int threads = 2) const;
  std::vector<Vec3> interpolate(const std::vector<Vec3>& values, const std::vector<SphereLocation>& at,
                                int threads = 2) const;

  const std::vector<Vec3>& sphere() const { return sphere_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  int cells_per_face_side() const { return resolution_; }

 private:
  // b x c, c x a, a x b of a triangle (a, b, c): d . edge_normal[i] is
  // proportional to barycentric coordinate i of direction d.
  struct EdgeNormals {
    Vec3 n[3];
  };

  int cell_of(const Vec3& direction) const;
  int checked_cell_of(const Vec3& direction) const;  // throws for a zero or non-finite direction
  SphereLocation locate_in_cell(const Vec3& direction, int cell) const;
  void check_values(size_t rows) const;  // throws unless one row per vertex
  const Triangle& corners(const SphereLocation& location) const;  // throws for a bad triangle index

  std::vector<Vec3> sphere_;
  std::vector<Triangle> triangles_;
  std::vector<EdgeNormals> edge_normals_;
  int resolution_ = 1;               // cells along each cube-face side
  std::vector<int> cell_start_;      // CSR: triangles of cell c are cell_triangles_[cell_start_[c] ..]
  std::vector<int> cell_triangles_;
};

}  // namespace cmaps
