// The analytic derivatives the map optimizers descend on
// (intersurface/map_gradient.h), against central differences of the very
// functions they differentiate; then as both optimizers wire them into a
// moving vertex's trial (which corner moves, which Jacobian goes with
// which image), against differences of the trial's own energy on a real
// partition.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "consistent_maps/mesh_io.h"
#include "intersurface/chord_energy.h"
#include "intersurface/consistent_partition.h"
#include "intersurface/cross_patch_optimization.h"
#include "intersurface/map_gradient.h"
#include "intersurface/patch_energy.h"
#include "intersurface/patch_locator.h"
#include "intersurface/patch_parameterization.h"
#include "partition_fixtures.h"
#include "test_support.h"

namespace cmaps {
namespace {

// Central differences of energy(x0 + d) at step h; nothing where a side is refused (infinite).
template <class Energy>
std::optional<Vec2> differences(const Vec2& x0, double h, const Energy& energy) {
  Vec2 d;
  for (int axis = 0; axis < 2; ++axis) {
    Vec2 step = Vec2::Zero();
    step[axis] = h;
    const double plus = energy(x0 + step), minus = energy(x0 - step);
    if (!std::isfinite(plus) || !std::isfinite(minus)) return std::nullopt;
    d[axis] = (plus - minus) / (2 * h);
  }
  return d;
}

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
    ChordTriangle worked_out;
    triangle_energy(shape, corner, nullptr, &worked_out);
    PointGradient g;
    add_chord_gradient(shape, worked_out, moving, weight, g);
    return g;
  }
};

TEST(MapGradient, ChordEnergyGradientMatchesDifferences) {
  const MovingChord chord(Vec3(0.1, -0.3, 1));  // facing the chord triangle: no fold
  const double weight = 2.5;
  const PointGradient g = chord.gradient(weight);
  double folded = 0;
  const auto d = differences(Vec2::Zero(), 1e-6, [&](const Vec2& p) { return weight * chord.energy(p, &folded); });
  ASSERT_TRUE(d);
  for (int axis = 0; axis < 2; ++axis)
    EXPECT_NEAR(g.energy[axis], (*d)[axis], 1e-5 * std::abs((*d)[axis]) + 1e-8) << "axis " << axis;
  EXPECT_GT(g.energy.norm(), 0.1);
  EXPECT_EQ(g.folded, Vec2::Zero());  // nothing folded, nothing to unfold
}

TEST(MapGradient, FoldedAreaGradientMatchesDifferences) {
  const MovingChord chord(Vec3(-0.1, 0.3, -1));  // against the chord triangle: a fold
  const PointGradient g = chord.gradient(1);
  double folded = 0;
  chord.energy(Vec2::Zero(), &folded);
  ASSERT_GT(folded, 0);
  const auto d_folded = differences(Vec2::Zero(), 1e-6, [&](const Vec2& p) {
    double area = 0;
    chord.energy(p, &area);
    return area;
  });
  const auto d_energy = differences(Vec2::Zero(), 1e-6, [&](const Vec2& p) { return chord.energy(p, &folded); });
  ASSERT_TRUE(d_folded && d_energy);
  for (int axis = 0; axis < 2; ++axis) {
    EXPECT_NEAR(g.folded[axis], (*d_folded)[axis], 1e-6) << "axis " << axis;
    // The fold's fixed density adds area times a constant: the energy's
    // gradient is still the density's (the charge, 1e6 times the area, costs
    // the difference some digits).
    EXPECT_NEAR(g.energy[axis], (*d_energy)[axis], 1e-4 * std::abs((*d_energy)[axis]) + 1e-4) << "axis " << axis;
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

// How many trials' analytic gradients agree with differences of their
// energy to 1e-4, relative to the larger of the two, or both lie within
// `noise` of zero (the differences' rounding: the value's last digits over
// the step).
struct Agreement {
  int trials = 0, agreeing = 0;
  void add(const Vec2& analytic, const Vec2& differences, double noise = 0) {
    ++trials;
    agreeing += (analytic - differences).norm() <= 1e-4 * std::max(analytic.norm(), differences.norm()) + noise;
  }
  double share(const char* what) const {
    std::printf("  %s: %d of %d trials agree\n", what, agreeing, trials);
    return trials ? double(agreeing) / trials : 0;
  }
};

TEST(MapGradient, TheInPatchTrialsGradientIsItsEnergysDerivative) {
  // Each free vertex of every patch, in its patch's canonical triangle:
  // its triangles mapped onto B, and B's triangles around the vertices of B
  // its ring holds mapped back. The energy is smooth but where an image
  // crosses an edge of the other mesh (a kink the image's Jacobian, by
  // differences 1e-4 of the ring apart, may straddle), so nearly all agree;
  // a wrong corner or Jacobian would leave few.
  test::CactusPoses cactus;
  PartitionSide &a = cactus.p.sides[0], &b = cactus.p.sides[1];
  const PatchParameterization uv_a = parameterize_patches(a, cactus.p), uv_b = parameterize_patches(b, cactus.p);
  const int patches = int(cactus.p.triangles.size());
  std::vector<std::vector<int>> faces(patches), target_faces(patches);
  for (int f = 0; f < int(a.patch.size()); ++f) faces[a.patch[f]].push_back(f);
  for (int g = 0; g < int(b.patch.size()); ++g) target_faces[b.patch[g]].push_back(g);
  const std::vector<char> on_path = test::on_paths(a);
  const double scale = std::sqrt(side_area(a) / side_area(b));
  Agreement energy_gradient;
  int remapping = 0;  // trials whose gradient runs through re-mapped vertices of B too
  for (int t = 0; t < patches; ++t) {
    std::unordered_map<int, Vec2> uv = uv_a.uv[t];
    const PatchEnergy energy(a, uv, faces[t], b, uv_b.uv[t], target_faces[t], scale);
    for (const auto& [v, p0] : uv_a.uv[t]) {
      if (on_path[v] || v % 5 != 0) continue;
      const PatchEnergy::Hosted inside = energy.hosted(v);
      PointGradient gradient;
      if (!std::isfinite(energy.trial(v, p0, inside, &gradient).energy)) continue;
      const auto d = differences(p0, 1e-6 * inside.length,
                                 [&](const Vec2& q) { return energy.trial(v, q, inside).energy; });
      if (!d) continue;
      energy_gradient.add(gradient.energy, *d);
      remapping += !inside.vertices.empty();
    }
  }
  ASSERT_GT(energy_gradient.trials, 300);
  EXPECT_GT(remapping, energy_gradient.trials / 2);
  // Measured: 973 of 973.
  EXPECT_GT(energy_gradient.share("in-patch"), 0.95);
}

TEST(MapGradient, TheTrialsAcrossPathsGradientIsItsEnergysDerivative) {
  // Each free vertex of A in the plane of its base triangle developed with
  // its neighbours (its ring may reach into the next patches): the energy's
  // gradient, and where the ring holds a fold, the folded area's. Eight ->
  // skull after the sweeps inside the patches, where folds are left and
  // vertices were pushed up against kinks (a chord about to fold, an image
  // at an edge of B), so fewer agree. Not at the vertices on paths: B's
  // patches are embedded apart, so B's embedding turns a corner there and
  // the energy has no gradient.
  const test::EightSkull pair;
  const CrossPatchMap map(pair.p, pair.uv_a, pair.uv_b);
  const std::vector<char> on_path = test::on_paths(pair.p.sides[0]);
  Agreement energy_gradient, folded_gradient;
  int unfolding = 0;  // folded rings whose folded area moves with the vertex
  for (int v = 0; v < int(on_path.size()); ++v) {
    const std::optional<CrossPatchMap::RingTrial> at = map.ring_trial(v, Vec2::Zero(), true);
    if (on_path[v] || !at) continue;
    const double h = 1e-6 * at->length;
    const auto of_trial = [&](double CrossPatchMap::RingTrial::*value) {
      return differences(Vec2::Zero(), h, [&](const Vec2& d) {
        const std::optional<CrossPatchMap::RingTrial> there = map.ring_trial(v, d, false);
        return there ? (*there).*value : kChordInf;
      });
    };
    const std::optional<Vec2> energy = of_trial(&CrossPatchMap::RingTrial::energy),
                              folded = of_trial(&CrossPatchMap::RingTrial::folded);
    if (!energy || !folded) continue;
    energy_gradient.add(at->gradient.energy, *energy);
    if (at->folded == 0) continue;
    const double noise = 1e-12 * at->folded / h;
    folded_gradient.add(at->gradient.folded, *folded, noise);
    unfolding += folded->norm() > 100 * noise;
  }
  ASSERT_GT(energy_gradient.trials, 1000);
  // Measured: 1270 of 1320.
  EXPECT_GT(energy_gradient.share("energy, across paths"), 0.93);
  // Measured: 766 of 783, 699 of them unfolding.
  std::printf("  %d folded rings unfold as the vertex moves\n", unfolding);
  EXPECT_GT(unfolding, 500);
  EXPECT_GT(folded_gradient.share("folded area, across paths"), 0.95);
}

}  // namespace
}  // namespace cmaps
