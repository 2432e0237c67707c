#include "intersurface/hole_rims.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

// Per vertex: (hole, position in its loop); (-1, -1) off every rim.
std::unordered_map<int, std::pair<int, int>> rim_positions(const std::vector<std::vector<int>>& loops) {
  std::unordered_map<int, std::pair<int, int>> at;
  for (int h = 0; h < int(loops.size()); ++h)
    for (int i = 0; i < int(loops[h].size()); ++i) at[loops[h][i]] = {h, i};
  return at;
}

// Arc length from the loop's first vertex to each vertex, then the whole loop's at the end.
std::vector<double> arc_lengths(const TriangleMesh& mesh, const std::vector<int>& loop) {
  std::vector<double> at{0};
  for (std::size_t i = 1; i <= loop.size(); ++i)
    at.push_back(at.back() + (mesh.vertices[loop[i % loop.size()]] - mesh.vertices[loop[i - 1]]).norm());
  return at;
}

// The loop position whose arc length (cyclic, from `from` towards `to`) is nearest `fraction` of the gap.
int inside_gap(const std::vector<double>& arc, int from, int to, double fraction) {
  const int n = int(arc.size()) - 1;
  const double total = arc[n];
  const auto ahead = [&](int i) { return std::fmod(arc[i] - arc[from] + total, total); };
  const double gap = to == from ? total : ahead(to);
  int best = -1;
  for (int i = (from + 1) % n; i != to; i = (i + 1) % n)
    if (best < 0 || std::abs(ahead(i) - fraction * gap) < std::abs(ahead(best) - fraction * gap)) best = i;
  return best;
}

}  // namespace

std::vector<HoleRim> pair_hole_rims(const ClosedMesh& a, const ClosedMesh& b,
                                    const std::vector<std::array<int, 2>>& pairs, bool b_turned,
                                    const PathGuide& guide) {
  const int holes = int(a.loops.size());
  if (int(b.loops.size()) != holes) throw Error("internal error: the pair's hole counts differ");
  std::vector<std::vector<int>> loops_b = b.loops;
  if (b_turned)
    for (auto& loop : loops_b) std::reverse(loop.begin() + 1, loop.end());
  const auto at_a = rim_positions(a.loops), at_b = rim_positions(loops_b);

  // Holes paired by the pairs on their rims.
  std::vector<int> partner(holes, -1), taken(holes, -1);
  std::vector<std::vector<std::array<int, 2>>> on_rim(holes);  // positions in A's and B's loop
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto ia = at_a.find(pairs[k][0]), ib = at_b.find(pairs[k][1]);
    if ((ia == at_a.end()) != (ib == at_b.end()))
      throw InvalidInput("feature pair " + std::to_string(k) + " joins a vertex on a hole's rim to one on no rim");
    if (ia == at_a.end()) continue;
    const int h = ia->second.first, g = ib->second.first;
    if ((partner[h] >= 0 && partner[h] != g) || (taken[g] >= 0 && taken[g] != h))
      throw InvalidInput("feature pair " + std::to_string(k) + " pairs a hole with a second partner");
    partner[h] = g, taken[g] = h;
    on_rim[h].push_back({ia->second.second, ib->second.second});
  }
  // The others by nearest centres in A's frame.
  for (int h = 0; h < holes; ++h) {
    if (partner[h] >= 0) continue;
    std::vector<Vec3> free_centres;
    std::vector<int> free_holes;
    for (int g = 0; g < holes; ++g)
      if (taken[g] < 0) free_centres.push_back(b.mesh.vertices[b.centre(g)]), free_holes.push_back(g);
    const int g = free_holes[guide.nearest(a.mesh.vertices[a.centre(h)], free_centres)];
    partner[h] = g, taken[g] = h;
  }

  std::vector<HoleRim> rims;
  for (int h = 0; h < holes; ++h) {
    const int g = partner[h];
    const std::vector<int>&loop_a = a.loops[h], &loop_b = loops_b[g];
    std::vector<std::array<int, 2>> at = on_rim[h];
    std::sort(at.begin(), at.end());
    // The same cyclic order on B: B's positions rise from the smallest, once around.
    const auto lowest =
        std::min_element(at.begin(), at.end(), [](const auto& x, const auto& y) { return x[1] < y[1]; });
    for (std::size_t i = 1; i < at.size(); ++i) {
      const auto& p = at[(lowest - at.begin() + i - 1) % at.size()];
      const auto& q = at[(lowest - at.begin() + i) % at.size()];
      if (q[1] <= p[1])
        throw InvalidInput("the feature pairs on hole " + std::to_string(h) +
                           " of A run around it in another order on B");
    }
    if (at.empty()) {
      std::vector<Vec3> rim_b;
      for (int v : loop_b) rim_b.push_back(b.mesh.vertices[v]);
      at.push_back({0, guide.nearest(a.mesh.vertices[loop_a[0]], rim_b)});
    }
    const std::vector<double> arc_a = arc_lengths(a.mesh, loop_a), arc_b = arc_lengths(b.mesh, loop_b);
    while (at.size() < 3) {
      // The longest gap on A that still has a vertex inside on both rims, split at its middle.
      int best = -1;
      double longest = -1;
      for (std::size_t i = 0; i < at.size(); ++i) {
        const auto &p = at[i], &q = at[(i + 1) % at.size()];
        const int middle_a = inside_gap(arc_a, p[0], q[0], 0.5);
        if (middle_a < 0 || inside_gap(arc_b, p[1], q[1], 0.5) < 0) continue;
        const double total = arc_a.back();
        const double gap = at.size() == 1 ? total : std::fmod(arc_a[q[0]] - arc_a[p[0]] + total, total);
        if (gap > longest) longest = gap, best = int(i);
      }
      if (best < 0)
        throw InvalidInput("hole " + std::to_string(h) + " of A is too small for 3 features on its rim");
      const auto p = at[best], q = at[(best + 1) % at.size()];
      at.insert(at.begin() + best + 1, {inside_gap(arc_a, p[0], q[0], 0.5), inside_gap(arc_b, p[1], q[1], 0.5)});
      // Keep the order of A's positions for the next gaps.
      std::rotate(at.begin(), std::min_element(at.begin(), at.end()), at.end());
    }
    HoleRim rim;
    rim.centre = {a.centre(h), b.centre(g)};
    rim.loop = {loop_a, loop_b};
    for (const auto& p : at) rim.features.push_back({loop_a[p[0]], loop_b[p[1]]});
    rims.push_back(std::move(rim));
  }
  return rims;
}

}  // namespace cmaps
