// The stretch metric of a map from a domain triangulation to a surface
// (Sander et al. 2001; Praun & Hoppe 2003, thesis section 2.9).
//
// For a triangle with domain corners d0, d1, d2 and surface corners m0, m1,
// m2, J is the Jacobian of the linear map domain -> surface with singular
// values G >= g. L2 stretch = sqrt((G^2 + g^2) / 2), Linf stretch = G.
// Spherical maps are measured on their chordal triangles.
#pragma once
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

struct TriangleStretch {
  double l2 = 0;    // sqrt((G^2 + g^2) / 2); +inf for a degenerate domain triangle
  double linf = 0;  // G
};

// Stretch of the linear map from domain triangle (d0, d1, d2) to surface
// triangle (m0, m1, m2); the domain triangle may live in any plane of R^3.
TriangleStretch triangle_stretch(const Vec3& d0, const Vec3& d1, const Vec3& d2,
                                 const Vec3& m0, const Vec3& m1, const Vec3& m2);

struct SphericalMapReport {
  double surface_area = 0;
  double l2_stretch = 0;    // sqrt(sum(A_m L2^2) / A_M)
  double linf_stretch = 0;  // max over triangles
  double efficiency = 0;    // (A_M / 4 pi) / L2^2; 1 for an isometry
  int flipped = 0;          // chordal triangles with negative orientation
  int degenerate = 0;       // chordal triangles with (near) zero area
  double spherical_area_sum = 0;  // signed spherical areas; 4 pi for a bijection
  bool bijective() const;   // no flips, no degeneracies, area sum 4 pi
};

// `sphere` holds one unit vector per mesh vertex.
SphericalMapReport measure_spherical_map(const TriangleMesh& mesh, const std::vector<Vec3>& sphere);

// Signed area of the spherical triangle (a, b, c) of unit vectors; positive
// when counter-clockwise seen from outside.
double signed_spherical_area(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace cmaps
