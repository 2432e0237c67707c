// The analytic derivatives the map optimizers descend on
// (intersurface/map_gradient.h), against central differences of the very
// functions they differentiate.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "intersurface/chord_energy.h"
#include "intersurface/map_gradient.h"
#include "intersurface/patch_locator.h"

namespace cmaps {
namespace {

// A chord triangle whose corners 0 and 2 move with a point p of the plane
// (image_k(p) = base_k + J_k p), corner 1 stays.
struct MovingChord {
  SourceTriangle shape = source_triangle({Vec3(0, 0, 0), Vec3(1.2, 0.1, 0), Vec3(0.3, 0.9, 0.2)});
  std::array<Vec3, 3> base = {Vec3(0.1, -0.2, 0.05), Vec3(1.5, 0.3, -0.1), Vec3(0.2, 1.4, 0.3)};
  std::array<Jacobian, 3> jacobian;
  Vec3 normal;  // the surface's normal at every image

  explicit MovingChord(const Vec3& surface_normal) : normal(surface_normal) {
    jacobian[0] << 0.7, -0.2, 0.1, 1.1, 0.3, 0.2;
    jacobian[2] << -0.4, 0.9, 0.8, 0.1, 0.0, -0.6;
  }
  std::array<Image, 3> images(const Vec2& p) const {
    std::array<Image, 3> image;
    for (int k = 0; k < 3; ++k) image[k] = {base[k] + (k == 1 ? Vec3::Zero() : Vec3(jacobian[k] * p)), normal};
    return image;
  }
  // The energy at p, and the folded area into *folded.
  double energy(const Vec2& p, double* folded) const {
    const std::array<Image, 3> image = images(p);
    const Image* corner[3] = {&image[0], &image[1], &image[2]};
    *folded = 0;
    return triangle_energy(shape, corner, folded);
  }
  PointGradient gradient(double weight) const {
    const std::array<Image, 3> image = images(Vec2::Zero());
    const Image* corner[3] = {&image[0], &image[1], &image[2]};
    const Jacobian* moving[3] = {&jacobian[0], nullptr, &jacobian[2]};
    PointGradient g;
    add_chord_gradient(shape, corner, moving, weight, g);
    return g;
  }
};

TEST(MapGradient, ChordEnergyGradientMatchesDifferences) {
  const MovingChord chord(Vec3(0.1, -0.3, 1));  // facing the chord triangle: no fold
  const double weight = 2.5, h = 1e-6;
  const PointGradient g = chord.gradient(weight);
  for (int axis = 0; axis < 2; ++axis) {
    Vec2 d = Vec2::Zero();
    d[axis] = h;
    double folded = 0;
    const double difference = weight * (chord.energy(d, &folded) - chord.energy(-d, &folded)) / (2 * h);
    EXPECT_NEAR(g.energy[axis], difference, 1e-5 * std::abs(difference) + 1e-8) << "axis " << axis;
  }
  EXPECT_GT(g.energy.norm(), 0.1);
  EXPECT_EQ(g.folded, Vec2::Zero());  // nothing folded, nothing to unfold
}

TEST(MapGradient, FoldedAreaGradientMatchesDifferences) {
  const MovingChord chord(Vec3(-0.1, 0.3, -1));  // against the chord triangle: a fold
  const double h = 1e-6;
  const PointGradient g = chord.gradient(1);
  double folded = 0;
  chord.energy(Vec2::Zero(), &folded);
  ASSERT_GT(folded, 0);
  for (int axis = 0; axis < 2; ++axis) {
    Vec2 d = Vec2::Zero();
    d[axis] = h;
    double plus = 0, minus = 0;
    const double energy_plus = chord.energy(d, &plus), energy_minus = chord.energy(-d, &minus);
    EXPECT_NEAR(g.folded[axis], (plus - minus) / (2 * h), 1e-6) << "axis " << axis;
    // The fold's fixed density adds area times a constant: the energy's
    // gradient is still the density's (the charge, 1e6 times the area, costs
    // the difference some digits).
    const double difference = (energy_plus - energy_minus) / (2 * h);
    EXPECT_NEAR(g.energy[axis], difference, 1e-4 * std::abs(difference) + 1e-4) << "axis " << axis;
  }
}

TEST(MapGradient, HeldPointJacobianMatchesDifferences) {
  const std::array<Vec2, 3> corners = {Vec2(0, 0), Vec2(1, 0.2), Vec2(0.3, 1)};
  const std::array<Vec3, 3> positions = {Vec3(0, 0, 1), Vec3(2, 0.5, 0), Vec3(0.5, 1.5, -0.5)};
  const Vec2 point(0.45, 0.35);
  const double scale = 0.8, h = 1e-6;
  const auto image = [&](const std::array<Vec2, 3>& c) {
    const std::array<double, 3> w = barycentric(point, c[0], c[1], c[2]);
    return Vec3(scale * (w[0] * positions[0] + w[1] * positions[1] + w[2] * positions[2]));
  };
  for (int slot = 0; slot < 3; ++slot) {
    const Jacobian jacobian =
        held_point_jacobian(corners, slot, barycentric(point, corners[0], corners[1], corners[2]), positions, scale);
    for (int axis = 0; axis < 2; ++axis) {
      std::array<Vec2, 3> plus = corners, minus = corners;
      plus[slot][axis] += h;
      minus[slot][axis] -= h;
      const Vec3 difference = (image(plus) - image(minus)) / (2 * h);
      EXPECT_LT((jacobian.col(axis) - difference).norm(), 1e-6) << "slot " << slot << " axis " << axis;
    }
    EXPECT_GT(jacobian.norm(), 0.1);
  }
}

TEST(MapGradient, ImageJacobianOneSidedWhereASideHasNoImage) {
  const Jacobian linear = (Jacobian() << 1, 2, 3, 4, 5, 6).finished();
  const auto image = [&](const Vec2& p) -> std::optional<Vec3> {
    if (p.x() < 0) return std::nullopt;  // nothing left of the axis
    return Vec3(linear * p);
  };
  const Jacobian jacobian = image_jacobian(Vec2::Zero(), Vec3::Zero(), 1e-3, image);
  EXPECT_LT((jacobian - linear).norm(), 1e-9);
}

}  // namespace
}  // namespace cmaps
