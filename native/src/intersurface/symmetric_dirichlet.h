// The symmetric Dirichlet energy of the linear map between two triangles in
// space: |J|_F^2 + |J^-1|_F^2, 4 for an isometry, growing without bound as
// the image degenerates. |J|_F^2 = sum_i cot(angle_i of P) |opposite edge of
// Q|^2 / (2 area P) needs no common plane, and |J^-1|_F^2 = |J|_F^2 (area P /
// area Q)^2 for a 2x2 Jacobian.
#pragma once
#include <cmath>
#include <limits>

#include "consistent_maps/mesh.h"

namespace cmaps {

// The energy of P -> Q (+inf for a degenerate image); 0 with *area = 0 for a
// degenerate source, which carries no energy. *area receives P's area.
inline double symmetric_dirichlet(const Vec3 (&p)[3], const Vec3 (&q)[3], double* area) {
  const double ap = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  const double aq = 0.5 * (q[1] - q[0]).cross(q[2] - q[0]).norm();
  *area = ap;
  if (!(ap > 0)) return 0;
  if (!(aq > 0)) return std::numeric_limits<double>::infinity();
  double dirichlet = 0;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
    dirichlet += u.dot(v) / u.cross(v).norm() * (q[(i + 2) % 3] - q[(i + 1) % 3]).squaredNorm();
  }
  dirichlet /= 2 * ap;
  return dirichlet * (1 + (ap / aq) * (ap / aq));
}

}  // namespace cmaps
