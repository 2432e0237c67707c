// Expectations every inter-surface map must meet, whatever its genus.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "consistent_maps/intersurface_map.h"

namespace cmaps::test {

// Every image lies on a triangle of the target with barycentric weights >= 0 summing to 1.
inline void expect_valid_points(const std::vector<SurfacePoint>& points, const TriangleMesh& target) {
  for (const SurfacePoint& p : points) {
    ASSERT_GE(p.triangle, 0);
    ASSERT_LT(p.triangle, int(target.triangles.size()));
    double sum = 0;
    for (double w : p.barycentric) {
      EXPECT_GE(w, 0);
      sum += w;
    }
    EXPECT_NEAR(sum, 1, 1e-12);
  }
}

// Each feature's image is its partner vertex, weight exactly 1.
inline void expect_exact_features(const IntersurfaceResult& r, const TriangleMesh& a, const TriangleMesh& b) {
  for (const FeaturePair& f : r.features) {
    const SurfacePoint &on_b = r.a_to_b[f.a], &on_a = r.b_to_a[f.b];
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(on_b.barycentric[k], b.triangles[on_b.triangle][k] == f.b ? 1.0 : 0.0);
      EXPECT_EQ(on_a.barycentric[k], a.triangles[on_a.triangle][k] == f.a ? 1.0 : 0.0);
    }
    EXPECT_EQ(r.a_on_b[f.a], b.vertices[f.b]);
    EXPECT_EQ(r.b_on_a[f.b], a.vertices[f.a]);
  }
}

// Two maps of one pair are the same: every vertex's image, both ways, on the
// same triangle with the same weights, bit for bit.
inline void expect_same_images(const IntersurfaceResult& x, const IntersurfaceResult& y) {
  for (const auto side : {&IntersurfaceResult::a_to_b, &IntersurfaceResult::b_to_a}) {
    ASSERT_EQ((x.*side).size(), (y.*side).size());
    for (std::size_t v = 0; v < (x.*side).size(); ++v) {
      ASSERT_EQ((x.*side)[v].triangle, (y.*side)[v].triangle) << "vertex " << v;
      ASSERT_EQ((x.*side)[v].barycentric, (y.*side)[v].barycentric) << "vertex " << v;
    }
  }
}

// The point of `mesh`'s triangle t next to its corner k, as corner images
// take it: kCornerNudge of the way from the corner towards the other two.
inline Vec3 nudged_corner(const TriangleMesh& mesh, int t, int k) {
  const Triangle& c = mesh.triangles[t];
  return (1 - 2 * kCornerNudge) * mesh.vertices[c[k]] +
         kCornerNudge * (mesh.vertices[c[(k + 1) % 3]] + mesh.vertices[c[(k + 2) % 3]]);
}

// Per corner, the distance between its image and its vertex's image
// (`vertex_images`, positions on the target), relative to `scale`: a corner
// image lands next to its vertex's, on whichever side of a seam.
inline std::vector<double> corner_offsets(const std::vector<SurfacePoint>& corners, const TriangleMesh& source,
                                          const TriangleMesh& target, const std::vector<Vec3>& vertex_images,
                                          double scale) {
  const std::vector<Vec3> at = surface_positions(target, corners);
  std::vector<double> offsets(at.size());
  for (std::size_t i = 0; i < at.size(); ++i)
    offsets[i] = (at[i] - vertex_images[source.triangles[i / 3][i % 3]]).norm() / scale;
  return offsets;
}

// The largest of those.
inline double corner_offset(const std::vector<SurfacePoint>& corners, const TriangleMesh& source,
                            const TriangleMesh& target, const std::vector<Vec3>& vertex_images, double scale) {
  const std::vector<double> offsets = corner_offsets(corners, source, target, vertex_images, scale);
  return offsets.empty() ? 0 : *std::max_element(offsets.begin(), offsets.end());
}

}  // namespace cmaps::test
