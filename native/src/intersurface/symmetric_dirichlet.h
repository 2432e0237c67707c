// The symmetric Dirichlet energy of the linear map between two triangles in
// space: |J|_F^2 + |J^-1|_F^2, 4 for an isometry, growing without bound as
// the image degenerates. |J|_F^2 = sum_i cot(angle_i of P) |opposite edge of
// Q|^2 / (2 area P) needs no common plane, and |J^-1|_F^2 = |J|_F^2 (area P /
// area Q)^2 for a 2x2 Jacobian.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "consistent_maps/mesh.h"

namespace cmaps {

// What the energy needs of the source triangle P: its area and the
// cotangents of its angles. An optimizer moving only images computes it once.
struct SourceTriangle {
  double area = 0;
  double cot[3] = {0, 0, 0};
};

inline SourceTriangle source_triangle(const Vec3 (&p)[3]) {
  SourceTriangle s;
  s.area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  if (!(s.area > 0)) return s;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
    s.cot[i] = u.dot(v) / std::max(u.cross(v).norm(), 1e-300);
  }
  return s;
}

// |J|_F^2 of P -> Q (P not degenerate).
inline double dirichlet_term(const SourceTriangle& p, const Vec3 (&q)[3]) {
  double dirichlet = 0;
  for (int i = 0; i < 3; ++i) dirichlet += p.cot[i] * (q[(i + 2) % 3] - q[(i + 1) % 3]).squaredNorm();
  return dirichlet / (2 * p.area);
}

// The energy of P -> Q, given Q's normal (q1 - q0) x (q2 - q0): 0 for a
// degenerate source, which carries no energy, +inf for a degenerate image.
inline double symmetric_dirichlet(const SourceTriangle& p, const Vec3 (&q)[3], const Vec3& q_normal) {
  if (!(p.area > 0)) return 0;
  const double aq = 0.5 * q_normal.norm();
  if (!(aq > 0)) return std::numeric_limits<double>::infinity();
  return dirichlet_term(p, q) * (1 + (p.area / aq) * (p.area / aq));
}

// The energy of P -> Q; *area receives P's area.
inline double symmetric_dirichlet(const Vec3 (&p)[3], const Vec3 (&q)[3], double* area) {
  const SourceTriangle s = source_triangle(p);
  *area = s.area;
  return symmetric_dirichlet(s, q, (q[1] - q[0]).cross(q[2] - q[0]));
}

}  // namespace cmaps
