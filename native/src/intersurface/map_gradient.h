// The derivative of the map optimizers' energy (chord_energy.h) by one
// moving vertex's canonical point, for their descent (descent_step.h): the
// analytic gradient of each chord triangle's energy by its corners' image
// positions, chained with how those images move with the point. Worked out
// once per step instead of four evaluations of the whole ring.
#pragma once
#include <Eigen/Core>
#include <array>
#include <optional>

#include "intersurface/chord_energy.h"

namespace cmaps {

using Jacobian = Eigen::Matrix<double, 3, 2>;  // an image position's derivative by a canonical point

// Of the energy, and of the folded area (what a ring holding a fold lowers first).
struct PointGradient {
  Vec2 energy = Vec2::Zero(), folded = Vec2::Zero();
};

// Adds triangle_energy(s, image), times `weight`, and the folded area it
// counts, differentiated through the corners whose image moves with the
// point (jacobian[k] not null), from what triangle_energy worked out
// (`chord`). Nothing where the energy is 0 or infinite.
inline void add_chord_gradient(const SourceTriangle& s, const ChordTriangle& chord, const Jacobian* jacobian[3],
                               double weight, PointGradient& gradient) {
  if (!chord.finite) return;
  const Vec3(&q)[3] = chord.q;
  const double aq = chord.aq, dirichlet = chord.dirichlet, ratio = (s.area / aq) * (s.area / aq);
  const Vec3 unit_normal = chord.nq / (2 * aq), surface = chord.normal.normalized();
  const bool fold = chord.nq.dot(surface) < 0;
  for (int k = 0; k < 3; ++k) {
    if (!jacobian[k]) continue;
    const Vec3 &a = q[(k + 1) % 3], &b = q[(k + 2) % 3];
    const Vec3 d_dirichlet = (s.cot[(k + 1) % 3] * (q[k] - b) + s.cot[(k + 2) % 3] * (q[k] - a)) / s.area;
    const Vec3 d_area = 0.5 * unit_normal.cross(b - a);
    const Vec3 d_energy = s.area * ((1 + ratio) * d_dirichlet - 2 * ratio / aq * dirichlet * d_area);
    gradient.energy += weight * jacobian[k]->transpose() * d_energy;
    // The folded area, -nq . surface / 2.
    if (fold) gradient.folded += jacobian[k]->transpose() * (-0.5 * (a - b).cross(surface));
  }
}

// The derivative of image(p) at p by central differences (one-sided where a
// side has no image); image(x) returns the position or nothing.
template <class ImageAt>
Jacobian image_jacobian(const Vec2& p, const Vec3& at_p, double h, const ImageAt& image) {
  Jacobian jacobian = Jacobian::Zero();
  for (int axis = 0; axis < 2; ++axis) {
    Vec2 d = Vec2::Zero();
    d[axis] = h;
    const std::optional<Vec3> plus = image(p + d), minus = image(p - d);
    if (plus && minus) jacobian.col(axis) = (*plus - *minus) / (2 * h);
    else if (plus) jacobian.col(axis) = (*plus - at_p) / h;
    else if (minus) jacobian.col(axis) = (at_p - *minus) / h;
  }
  return jacobian;
}

// The derivative of the image of a fixed point of the plane held by the
// triangle `corners` (image: weights times `positions`, scaled) by corner
// `slot`, the moving one: the other two corners' weights change by
// -w[slot] M^-1 dp, M their offsets from the moving corner.
inline Jacobian held_point_jacobian(const std::array<Vec2, 3>& corners, int slot, const std::array<double, 3>& weights,
                                    const std::array<Vec3, 3>& positions, double scale) {
  const int a = (slot + 1) % 3, b = (slot + 2) % 3;
  Eigen::Matrix2d offsets;
  offsets << corners[a] - corners[slot], corners[b] - corners[slot];
  const double det = offsets.determinant();
  if (det == 0) return Jacobian::Zero();
  Jacobian edges;
  edges << positions[a] - positions[slot], positions[b] - positions[slot];
  return scale * edges * (-weights[slot] * offsets.inverse());
}

}  // namespace cmaps
