#include "sphere/stretch_energy.h"

#include <cmath>
#include <limits>

namespace cmaps {

FaceWeights face_weights(const Triangle& t, const std::vector<const std::vector<Vec3>*>& geometries,
                         bool regularizer_only) {
  FaceWeights w{0, 0, 0};
  for (const auto* x : geometries) {
    const Vec3 &m0 = (*x)[t[0]], &m1 = (*x)[t[1]], &m2 = (*x)[t[2]];
    const double area = 0.5 * (m1 - m0).cross(m2 - m0).norm();
    if (!regularizer_only) {
      w[0] += area * (m1 - m2).squaredNorm();
      w[1] += area * (m2 - m0).squaredNorm();
      w[2] += area * (m0 - m1).squaredNorm();
    }
    // A thousandth of the weights of an equilateral triangle with the same
    // edge lengths: keeps sliver and zero-area surface triangles (common in
    // scans and coarse levels) from being squashed to nothing on the sphere.
    const double squared_edges = (m1 - m2).squaredNorm() + (m2 - m0).squaredNorm() + (m0 - m1).squaredNorm();
    const double regular = 1e-3 * (std::sqrt(3.0) / 4) * squared_edges * squared_edges / 9;
    for (double& wi : w) wi += regular;
  }
  return w;
}

bool chordal_triangle_valid(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 pa = a - p, pb = b - p;
  const double det = pa.cross(pb).dot(p);
  return det > 1e-15 * (pa.squaredNorm() + pb.squaredNorm());
}

double corner_energy(const Vec3& p, const Vec3& a, const Vec3& b, const FaceWeights& w, Vec3* gradient) {
  const Vec3 pa = a - p, pb = b - p, ab = b - a;
  const Vec3 n = pa.cross(pb);
  const double det = n.dot(p);
  if (!(det > 1e-15 * (pa.squaredNorm() + pb.squaredNorm()))) return std::numeric_limits<double>::infinity();
  const double len = n.norm();
  // Corner dot products: at p, at a, at b.
  const double wp = pa.dot(pb), wa = -pa.dot(ab), wb = pb.dot(ab);
  const double numerator = w[0] * wp + w[1] * wa + w[2] * wb;
  const double energy = numerator / (2 * len * det);
  if (gradient) {
    const Vec3 d_numerator = w[0] * (-pa - pb) + (w[1] - w[2]) * ab;
    const Vec3 d_len = n.cross(ab) / len;  // gradient of |n| = (a - b) x n / |n|
    const Vec3 d_det = a.cross(b);
    *gradient += d_numerator / (2 * len * det) - energy * (d_len / len + d_det / det);
  }
  return energy;
}

}  // namespace cmaps
