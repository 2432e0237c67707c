// PatchLocator's grid against a scan of every triangle, on layouts of long
// thin triangles like the patch embeddings': the same triangle and weights for
// points inside, on edges and corners, and a rounding error or more outside;
// and with a hint, the same as without.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "consistent_maps/errors.h"
#include "intersurface/patch_locator.h"

namespace cmaps {
namespace {

struct Layout {
  std::vector<Vec2> points;
  std::vector<std::array<Vec2, 3>> corners;
};

// A fan of `n` slivers from the canonical triangle's apex to its base.
Layout fan(int n) {
  Layout layout;
  const Vec2 apex(0.5, std::sqrt(3.0) / 2);
  layout.points.push_back(apex);
  for (int k = 0; k <= n; ++k) layout.points.emplace_back(double(k) / n, 0);
  for (int k = 0; k < n; ++k) layout.corners.push_back({apex, layout.points[k + 1], layout.points[k + 2]});
  return layout;
}

// A grid of nx by ny cells (1.3 / nx wide, 1 / ny tall), each cut into two
// triangles, turned by `angle` about the canonical triangle's middle: with few
// rows, long thin triangles whose bounding boxes overlap many others, some
// outside the unit square.
Layout turned_grid(int nx, int ny, double angle) {
  Layout layout;
  const Vec2 middle(0.5, 0.3);
  const auto at = [&](int i, int j) {
    const Vec2 q(1.3 * i / nx - 0.65, 1.0 * j / ny - 0.5);
    return Vec2(middle + Vec2(std::cos(angle) * q.x() - std::sin(angle) * q.y(),
                              std::sin(angle) * q.x() + std::cos(angle) * q.y()));
  };
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) layout.points.push_back(at(i, j));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      layout.corners.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      layout.corners.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return layout;
}

// What a scan of every triangle finds: the first surely holding p, else the
// first p is least outside of.
Holder scanned(const std::vector<std::array<Vec2, 3>>& corners, const Vec2& p) {
  std::vector<int> all(corners.size());
  std::iota(all.begin(), all.end(), 0);
  Holder best;
  find_holder(p, all.begin(), all.end(), [&](int i, std::array<Vec2, 3>& c) { c = corners[i]; }, best);
  return best;
}

// Queries: scattered points, every corner and edge midpoint, and each of
// those nudged a rounding error and a little more off.
std::vector<Vec2> queries(const Layout& layout) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> x(-0.3, 1.3), y(-0.3, 1.1);
  std::vector<Vec2> result;
  for (int q = 0; q < 3000; ++q) result.emplace_back(x(random), y(random));
  std::vector<Vec2> exact = layout.points;
  for (const auto& c : layout.corners)
    for (int k = 0; k < 3; ++k) exact.push_back((c[k] + c[(k + 1) % 3]) / 2);
  for (const Vec2& p : exact)
    for (double off : {0.0, 1e-13, -1e-13, 1e-7, -1e-7}) result.push_back(p + Vec2(off, -0.5 * off));
  return result;
}

void expect_as_scanned(const Layout& layout) {
  std::vector<int> faces(layout.corners.size());
  for (int i = 0; i < int(faces.size()); ++i) faces[i] = 10 * i + 3;  // any face numbers
  const PatchLocator locator(faces, layout.corners);
  for (const Vec2& p : queries(layout)) {
    const auto [face, weights] = locator.locate(p);
    const Holder expected = scanned(layout.corners, p);
    if (expected.score < -1e-9) {
      // Outside every triangle: the grid's cell is scanned first, so of equally
      // near triangles another may come first; it must be as near.
      const int i = face / 10;
      const auto w = barycentric(p, layout.corners[i][0], layout.corners[i][1], layout.corners[i][2]);
      ASSERT_EQ(std::min({w[0], w[1], w[2]}), expected.score) << "at (" << p.x() << ", " << p.y() << ")";
      continue;
    }
    ASSERT_EQ(face, faces[expected.face]) << "at (" << p.x() << ", " << p.y() << ")";
    double sum = 0;
    for (double w : expected.weights) sum += std::max(0.0, w);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(weights[k], std::max(0.0, expected.weights[k]) / sum);
  }
}

// A hint (the triangle found, its neighbours in the list, one far off, none,
// a face the locator does not hold) never changes what is found: on edges and
// corners, where the hint holds p too, the grid's triangle still comes out.
void expect_hints_change_nothing(const Layout& layout) {
  std::vector<int> faces(layout.corners.size());
  for (int i = 0; i < int(faces.size()); ++i) faces[i] = 10 * i + 3;
  const PatchLocator locator(faces, layout.corners);
  const int n = int(faces.size());
  for (const Vec2& p : queries(layout)) {
    const auto found = locator.locate(p);
    const int i = found.first / 10;
    for (int hint : {found.first, faces[(i + 1) % n], faces[(i + n - 1) % n], faces[(i + n / 2) % n], -1, 7})
      ASSERT_EQ(locator.locate(p, hint), found) << "at (" << p.x() << ", " << p.y() << "), hint " << hint;
  }
}

TEST(PatchLocator, FanOfSliversAsScanned) { expect_as_scanned(fan(400)); }

TEST(PatchLocator, TurnedThinGridAsScanned) {
  for (double angle : {0.0, 0.5, 1.2, 2.0}) expect_as_scanned(turned_grid(120, 2, angle));
}

TEST(PatchLocator, HintsChangeNothing) {
  expect_hints_change_nothing(fan(400));
  for (double angle : {0.0, 1.2}) expect_hints_change_nothing(turned_grid(120, 2, angle));
}

TEST(PatchLocator, EmptyLayoutRefused) {
  const PatchLocator locator({}, {});
  EXPECT_THROW(locator.locate(Vec2(0.5, 0.5)), Error);
}

}  // namespace
}  // namespace cmaps
