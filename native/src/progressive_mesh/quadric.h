// Garland-Heckbert quadric error: the area-weighted sum of squared distances
// to a set of planes, stored as the upper triangle of a symmetric 4x4 matrix.
#pragma once
#include <array>

#include "consistent_maps/mesh.h"

namespace cmaps {

class Quadric {
 public:
  // Plane through the triangle (p0, p1, p2), weighted by its area.
  static Quadric of_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    Quadric q;
    const Vec3 n2 = (p1 - p0).cross(p2 - p0);  // twice the area times the unit normal
    const double len = n2.norm();
    if (!(len > 0)) return q;
    const Vec3 n = n2 / len;
    const double d = -n.dot(p0), w = 0.5 * len;
    const double v[4] = {n.x(), n.y(), n.z(), d};
    int k = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) q.m_[k++] = w * v[i] * v[j];
    return q;
  }

  Quadric& operator+=(const Quadric& o) {
    for (int i = 0; i < 10; ++i) m_[i] += o.m_[i];
    return *this;
  }

  // x^T Q x for the homogeneous point (p, 1).
  double error(const Vec3& p) const {
    const double x = p.x(), y = p.y(), z = p.z();
    return m_[0] * x * x + 2 * m_[1] * x * y + 2 * m_[2] * x * z + 2 * m_[3] * x + m_[4] * y * y +
           2 * m_[5] * y * z + 2 * m_[6] * y + m_[7] * z * z + 2 * m_[8] * z + m_[9];
  }

 private:
  std::array<double, 10> m_{};
};

}  // namespace cmaps
