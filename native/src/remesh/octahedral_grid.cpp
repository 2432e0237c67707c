#include "consistent_maps/octahedral_grid.h"

#include <array>
#include <map>
#include <string>

#include "consistent_maps/errors.h"

namespace cmaps {

OctahedralGrid octahedral_grid(int n) {
  if (n < 2 || n % 2 != 0 || n > 46340)
    throw InvalidInput("octahedral grid: n must be even and in [2, 46340], got " + std::to_string(n));
  const int h = n / 2, side = n + 1;
  OctahedralGrid grid;
  grid.n = n;
  grid.pixel_vertex.resize(static_cast<size_t>(side) * side);
  // Integer octahedron points make the boundary identification exact.
  std::map<std::array<int, 3>, int> index;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int a = j - h, b = i - h, z = h - std::abs(a) - std::abs(b);
      const std::array<int, 3> p = z >= 0 ? std::array<int, 3>{a, b, z}
                                          : std::array<int, 3>{(a > 0 ? 1 : -1) * (h - std::abs(b)),
                                                               (b > 0 ? 1 : -1) * (h - std::abs(a)), z};
      const auto [it, added] = index.emplace(p, static_cast<int>(grid.sphere.size()));
      if (added) grid.sphere.push_back(Vec3(p[0], p[1], p[2]).normalized());
      grid.pixel_vertex[static_cast<size_t>(i) * side + j] = it->second;
    }
  }
  // Each square is split along the diagonal parallel to the diamond edge of
  // its quadrant, so every triangle lies on one octahedron face. (a, b, z)
  // is right-handed and the unfolding preserves orientation, so
  // counter-clockwise in (a, b) is counter-clockwise seen from outside.
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int v00 = grid.vertex(i, j), v01 = grid.vertex(i, j + 1);
      const int v10 = grid.vertex(i + 1, j), v11 = grid.vertex(i + 1, j + 1);
      const bool same_sign_quadrant = (2 * (j - h) + 1) * (2 * (i - h) + 1) > 0;
      if (same_sign_quadrant) {  // anti-diagonal (a+1, b) - (a, b+1)
        grid.triangles.push_back({v00, v01, v10});
        grid.triangles.push_back({v01, v11, v10});
      } else {  // main diagonal (a, b) - (a+1, b+1)
        grid.triangles.push_back({v00, v01, v11});
        grid.triangles.push_back({v00, v11, v10});
      }
    }
  }
  return grid;
}

}  // namespace cmaps
