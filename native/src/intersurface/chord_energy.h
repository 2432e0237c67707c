// The energy the patch-wise map optimizers lower (patch_map_optimization.h,
// cross_patch_optimization.h): each triangle of one side mapped linearly onto
// the chord triangle of its corners' images on the other side (scaled to the
// first side's area), area times symmetric Dirichlet density, a fold (image
// facing against the surface there) charged a fixed high density more. (A
// fold charged the fixed density alone could be squeezed into a needle for
// nothing: feline -> cup's mean was 3.6 million, from a few such needles.)
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "intersurface/consistent_partition.h"
#include "intersurface/patch_locator.h"
#include "intersurface/surface_image.h"
#include "intersurface/symmetric_dirichlet.h"

namespace cmaps {

constexpr double kChordInf = std::numeric_limits<double>::infinity();
constexpr double kFoldPenalty = 1e6;  // added energy density of an image triangle facing against the surface there
// A vertex whose ring holds more target vertices than this stays where it is:
// each trial re-maps all of them (such rings lie where the target is
// compressed most, e.g. between unrelated feature pairs).
constexpr int kMaxRemapped = 256;

// The positions of the corners of `side`'s triangle f.
inline std::array<Vec3, 3> corner_positions(const PartitionSide& side, int f) {
  const Triangle& t = side.mesh.triangles()[f];
  return {side.mesh.position(t[0]), side.mesh.position(t[1]), side.mesh.position(t[2])};
}

// Triangle f of `side` as the source of a map.
inline SourceTriangle shape_of(const PartitionSide& side, int f) {
  const std::array<Vec3, 3> p = corner_positions(side, f);
  return source_triangle({p[0], p[1], p[2]});
}

// The image of the point with weights w in `side`'s triangle `face`, scaled.
inline Image image_in(const PartitionSide& side, int face, const std::array<double, 3>& w, double scale) {
  const auto [a, b, c] = corner_positions(side, face);
  return {scale * (w[0] * a + w[1] * b + w[2] * c), (b - a).cross(c - a).normalized()};
}

// What triangle_energy works out on its way, for its derivative (map_gradient.h).
struct ChordTriangle {
  Vec3 q[3];          // the corners' images
  Vec3 nq, normal;    // (q1 - q0) x (q2 - q0); the surface's normal there, not normalized
  double aq = 0, dirichlet = 0;
  bool finite = false;  // false where the energy is 0 (no source area) or inf
};

// Area times symmetric Dirichlet density of the linear map from a triangle
// onto the chord triangle of its corners' images, plus kFoldPenalty times
// the area when that faces against the surface (then *folded, if given, is
// raised by its area projected on the surface); inf when degenerate. `chord`,
// if given, gets what was worked out.
inline double triangle_energy(const SourceTriangle& s, const Image* image[3], double* folded = nullptr,
                              ChordTriangle* chord = nullptr) {
  if (s.area <= 0) return 0;
  const Vec3 nq = (image[1]->position - image[0]->position).cross(image[2]->position - image[0]->position);
  const double aq = 0.5 * nq.norm();
  if (aq <= 1e-14 * s.area) return kChordInf;
  const Vec3 q[3] = {image[0]->position, image[1]->position, image[2]->position};
  const double dirichlet = dirichlet_term(s, q);
  const double density = dirichlet * (1 + (s.area / aq) * (s.area / aq));
  const Vec3 normal = surface_normal(image);
  if (chord) *chord = {{q[0], q[1], q[2]}, nq, normal, aq, dirichlet, true};
  if (!(nq.dot(normal) < 0)) return s.area * density;
  if (folded) *folded -= 0.5 * nq.dot(normal.normalized());
  return s.area * (density + kFoldPenalty);
}

// The weights clamped to the triangle and normalized.
inline std::array<double, 3> clamped(std::array<double, 3> w) {
  double sum = 0;
  for (double& x : w) sum += (x = std::max(0.0, x));
  for (double& x : w) x = sum > 0 ? x / sum : 1.0 / 3;
  return w;
}

// Twice the signed area of the 2D triangle (a, b, c).
inline double twice_signed_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d x = b - a, y = c - a;
  return x.x() * y.y() - x.y() * y.x();
}

// The total area of a side's triangles.
inline double side_area(const PartitionSide& side) {
  double area = 0;
  for (const Triangle& t : side.mesh.triangles())
    area += 0.5 * (side.mesh.position(t[1]) - side.mesh.position(t[0]))
                      .cross(side.mesh.position(t[2]) - side.mesh.position(t[0]))
                      .norm();
  return area;
}

}  // namespace cmaps
