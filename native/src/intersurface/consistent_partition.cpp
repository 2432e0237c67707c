#include "intersurface/consistent_partition.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "intersurface/partition_network.h"
#include "intersurface/path_guide.h"
#include "intersurface/tree_cotree.h"
#include "mesh/union_find.h"
#include "paths/mesh_search.h"

namespace cmaps {
namespace {

using partition::End;
using partition::Side;
using partition::tree_cotree_cycle;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kNearest = 10;          // tree candidates: each feature's nearest features
constexpr int kJoinAttempts = 40;     // corner pairs tried to join two boundary walks
constexpr int kDiagonalAttempts = 8;  // nearest corner pairs traced to split a face (the shortest is laid)
constexpr int kExtremityNeighbours = 8;  // features whose mean distance marks an extremity (thesis 5.4)
constexpr int kSideNeighbours = 6;       // nearby features whose side a tree path must keep on both meshes

// How a new path may attach at one of its features: anywhere on both meshes,
// anywhere on A and through the corresponding sector on B, or in the sector
// after a given end (counter-clockwise) on both.
struct Attach {
  enum Mode { kFree, kMatch, kFixed } mode = kMatch;
  End after;
};

// A corner of a face: feature f, in the sector after the `index`-th end around it.
struct Corner {
  int feature = -1;
  int index = -1;
};

struct Walk {
  std::vector<Corner> corners;
  std::vector<End> after;    // per corner: the end it follows (names it while ends are added elsewhere)
  std::vector<End> leaving;  // per corner: the end through which the walk leaves it
};

class Partitioner {
 public:
  Partitioner(const TriangleMesh& a, const TriangleMesh& b, const std::vector<std::array<int, 2>>& features, int genus,
              const PartitionHoles& holes)
      : genus_(genus), guide_(pair_positions(a, features, 0), pair_positions(b, features, 1), a, b), holes_(holes) {
    const bool fans = !holes.rims.empty();
    sides_.emplace_back(a, fans ? holes.first_fan[0] : int(a.triangles.size()));
    sides_.emplace_back(b, fans ? holes.first_fan[1] : int(b.triangles.size()));
    for (int s = 0; s < 2; ++s) scale_[s] = std::sqrt(std::max(surface_area(s == 0 ? a : b), 1e-300));
    for (const auto& f : features) add_pair(f[0], f[1]);
  }

  ConsistentPartition run() {
    seed_holes();
    tree();
    handles();
    complete();
    return assemble();
  }

 private:
  static std::vector<Vec3> pair_positions(const TriangleMesh& m, const std::vector<std::array<int, 2>>& pairs,
                                          int s) {
    std::vector<Vec3> positions;
    for (const auto& p : pairs) positions.push_back(m.vertices[p[s]]);
    return positions;
  }

  int add_pair(int va, int vb) {
    sides_[0].add_feature(va);
    sides_[1].add_feature(vb);
    return int(sides_[0].feature.size()) - 1;
  }

  // Summed, size-normalized distance between two features on both meshes.
  double cost(int i, int j) const {
    double c = 0;
    for (int s = 0; s < 2; ++s) {
      const Side& side = sides_[s];
      c += (side.mesh.position(side.feature[i]) - side.mesh.position(side.feature[j])).norm() / scale_[s];
    }
    return c;
  }

  // Traces a path between features i and j on A, then on B through the
  // sectors it used on A; lays both. False when either has no path.
  bool connect(int i, int j, const Attach& at_i, const Attach& at_j) {
    Traced traced;
    if (!trace(i, j, at_i, at_j, traced)) return false;
    lay(i, j, traced);
    return true;
  }

  // A corresponding pair of traced node sequences (search nodes as in mesh_search.h).
  struct Traced {
    std::vector<int> nodes[2];
    int vertices[2] = {0, 0};
    double length = 0;  // summed, size-normalized
  };

  // How a path may leave (or enter) a feature on one side: anywhere, or in
  // the sector after end `after`; a cut (the ring position of a temporary
  // path's step into the feature) keeps only the part of that sector before
  // it or after it, counter-clockwise (half the ring when nothing else ends there).
  struct Gate {
    bool restricted = false;
    End after;
    double cut = -1;
    bool before_cut = false;
  };

  Sector gate(int s, int f, const Gate& g, const std::vector<End>& around, int vertices, bool midpoints) const {
    const Side& side = sides_[s];
    Sector sector =
        g.restricted ? side.after(f, g.after, around, vertices, midpoints) : side.positions(f, vertices, midpoints);
    if (g.cut < 0) return sector;
    const double size = sector.size;
    if (sector.everything) {
      sector.everything = false;
      sector.lo = g.before_cut ? std::fmod(g.cut + size / 2, size) : g.cut;
      sector.span = size / 2;
    } else {
      const double rel = std::fmod(g.cut - sector.lo + size, size);
      if (rel <= 0 || rel >= sector.span) return sector;  // the cut lies in another sector
      if (g.before_cut) {
        sector.span = rel;
      } else {
        sector.lo = g.cut;
        sector.span -= rel;
      }
    }
    return sector;
  }

  // Side s's shortest path from feature i to j through the gates, over
  // vertices and, when that finds none, edge midpoints too; empty when none.
  std::vector<int> trace_on(int s, int i, int j, const Gate& at_i, const Gate& at_j, const Side::StepFactor* factor,
                            int& vertices) const {
    const Side& side = sides_[s];
    const std::vector<End> around_i = side.ends(i, edges_), around_j = side.ends(j, edges_);
    const auto gated = [](const Gate& g) { return g.restricted || g.cut >= 0; };
    for (bool midpoints : {false, true}) {
      vertices = side.mesh.vertex_count();
      const Sector leave = gate(s, i, at_i, around_i, vertices, midpoints);
      const Sector enter = gate(s, j, at_j, around_j, vertices, midpoints);
      std::vector<int> nodes =
          side.trace(i, j, gated(at_i) ? &leave : nullptr, gated(at_j) ? &enter : nullptr, midpoints, factor);
      if (!nodes.empty()) return nodes;
    }
    return {};
  }

  // The ends after which side s's half of `traced` leaves i and enters j.
  std::array<End, 2> gaps(int s, int i, int j, const Traced& traced) const {
    const Side& side = sides_[s];
    const std::vector<int>& nodes = traced.nodes[s];
    return {side.gap_of(i, nodes[1], side.ends(i, edges_), traced.vertices[s], true),
            side.gap_of(j, nodes[nodes.size() - 2], side.ends(j, edges_), traced.vertices[s], true)};
  }

  // The step factor keeping B's search near A's half of `traced` (path_guide.h).
  Side::StepFactor near_a(const Traced& traced) const {
    std::vector<Vec3> on_a;
    for (int node : traced.nodes[0]) on_a.push_back(node_position(sides_[0].mesh, node, traced.vertices[0]));
    return guide_.near(on_a);
  }

  double length(int s, const Traced& traced) const {
    return path_length(sides_[s].mesh, traced.nodes[s], traced.vertices[s]) / scale_[s];
  }

  // With a `bound`, gives up (false) once the pair cannot be shorter: A's
  // traced length plus B's straight distance reaches it.
  bool trace(int i, int j, const Attach& at_i, const Attach& at_j, Traced& traced, double bound = kInf) const {
    std::array<End, 2> on_a;  // the sectors A's half used, for kMatch
    for (int s = 0; s < 2; ++s) {
      const auto gate_of = [&](const Attach& at, const End& used) {
        Gate g;
        g.restricted = at.mode == Attach::kFixed || (at.mode == Attach::kMatch && s == 1);
        g.after = at.mode == Attach::kFixed ? at.after : used;
        return g;
      };
      const Side::StepFactor guide = s == 1 ? near_a(traced) : Side::StepFactor();
      traced.nodes[s] = trace_on(s, i, j, gate_of(at_i, on_a[0]), gate_of(at_j, on_a[1]), s == 1 ? &guide : nullptr,
                                 traced.vertices[s]);
      if (traced.nodes[s].empty()) return false;
      traced.length += length(s, traced);
      if (s == 0) {
        on_a = gaps(0, i, j, traced);
        const Side& b = sides_[1];
        if (traced.length + (b.mesh.position(b.feature[i]) - b.mesh.position(b.feature[j])).norm() / scale_[1] >= bound)
          return false;
      }
    }
    return true;
  }

  void lay(int i, int j, const Traced& traced) {
    const std::vector<int>* nodes = traced.nodes;
    for (int s = 0; s < 2; ++s) sides_[s].lay(nodes[s], traced.vertices[s]);
    edges_.push_back({i, j});
  }

  // Phase 0, with holes: each rim between its features and a spoke from its
  // centre to each, on both meshes alike; each hole's fan is then cut into
  // triangles of three features that no later path enters (the fan's
  // vertices are all blocked and its faces closed).
  void seed_holes() {
    std::unordered_map<int, int> feature_of;  // A's vertex -> feature
    for (int f = 0; f < int(sides_[0].feature.size()); ++f) feature_of[sides_[0].feature[f]] = f;
    const auto feature = [&](int v) {
      const auto it = feature_of.find(v);
      if (it == feature_of.end()) throw Error("internal error: a rim feature or hole centre is no feature");
      return it->second;
    };
    for (const HoleRim& rim : holes_.rims) {
      const int centre = feature(rim.centre[0]), k = int(rim.features.size());
      centres_.push_back(centre);
      for (int i = 0; i < k; ++i) {
        const int from = feature(rim.features[i][0]), to = feature(rim.features[(i + 1) % k][0]);
        for (int s = 0; s < 2; ++s) {
          const std::vector<int>& loop = rim.loop[s];
          const int n = int(loop.size());
          int at = int(std::find(loop.begin(), loop.end(), rim.features[i][s]) - loop.begin());
          std::vector<int> path{loop[at]};
          do {
            at = (at + 1) % n;
            path.push_back(loop[at]);
          } while (loop[at] != rim.features[(i + 1) % k][s]);
          sides_[s].register_path(path);
        }
        edges_.push_back({from, to});
      }
      for (int i = 0; i < k; ++i) {
        for (int s = 0; s < 2; ++s) sides_[s].register_path({rim.centre[s], rim.features[i][s]});
        edges_.push_back({centre, feature(rim.features[i][0])});
      }
      seeded_cycles_ += k;  // k rim paths and k spokes among k + 1 features
    }
  }

  bool is_centre(int f) const { return std::find(centres_.begin(), centres_.end(), f) != centres_.end(); }

  // Phase 1: a spanning tree of the features, Kruskal over pairs of nearby
  // features by cost, with the two swirl heuristics of thesis 5.4 (swirls:
  // paths winding round other features, so the patches twist): while a
  // feature at an extremity has no path, only paths touching an extremity
  // are laid (else paths between other features go round an extremity's
  // base, on either side); a pair passing a nearby feature of another
  // component on different sides on A and B waits until nothing else joins
  // two components, and is then re-routed on one mesh to the other's side.
  void tree() {
    const int k = int(sides_[0].feature.size());
    std::vector<std::pair<double, std::array<int, 2>>> candidates;
    for (int i = 0; i < k; ++i) {
      std::vector<std::pair<double, int>> near;
      for (int j = 0; j < k; ++j)
        if (j != i) near.push_back({cost(i, j), j});
      std::sort(near.begin(), near.end());
      for (int n = 0; n < int(near.size()); ++n)
        if (n < kNearest || k <= 2 * kNearest)
          candidates.push_back({near[n].first, {std::min(i, near[n].second), std::max(i, near[n].second)}});
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    UnionFind components(k);
    int count = k;
    std::vector<int> degree(k, 0);
    const auto join = [&](int i, int j) {
      components.unite(i, j);
      --count;
      ++degree[i], ++degree[j];
    };
    for (const auto& e : edges_)  // the seeded holes
      if (components.find(e[0]) != components.find(e[1])) join(e[0], e[1]);
    const std::vector<char> extreme = extremities();
    bool extremities_first = true;
    std::vector<char> done(candidates.size(), 0);  // laid, untraceable or on the wrong side
    std::vector<size_t> waiting;                     // on the wrong side, by cost
    const Attach match{Attach::kMatch, {}};
    while (count > 1) {
      bool waits = false;  // an extremity without a path
      for (int f = 0; f < k; ++f) waits |= extremities_first && extreme[f] && !degree[f];
      bool laid = false;
      for (size_t c = 0; c < candidates.size() && !laid; ++c) {
        const auto [i, j] = candidates[c].second;
        if (done[c] || (waits && !extreme[i] && !extreme[j])) continue;
        done[c] = 1;
        Traced traced;
        if (components.find(i) == components.find(j) || is_centre(i) || is_centre(j) ||
            !trace(i, j, match, match, traced))
          continue;
        if (wrong_side(i, j, traced, components) >= 0) {
          ++delayed_;
          waiting.insert(std::upper_bound(waiting.begin(), waiting.end(), c), c);
          continue;
        }
        lay(i, j, traced);
        join(i, j);
        laid = true;
      }
      if (laid) continue;
      if (waits) {  // the extremities left cannot be joined first
        extremities_first = false;
        continue;
      }
      // Only pairs on the wrong side join components: the cheapest, re-routed.
      for (auto c = waiting.begin(); c != waiting.end() && !laid;) {
        const auto [i, j] = candidates[*c].second;
        c = waiting.erase(c);
        Traced traced;
        if (components.find(i) == components.find(j) || !trace(i, j, match, match, traced)) continue;
        const int n = wrong_side(i, j, traced, components);
        if (n >= 0 && reroute(i, j, n, traced)) ++rerouted_;
        lay(i, j, traced);
        join(i, j);
        laid = true;
      }
      if (!laid) throw Error("could not connect the features by a tree of corresponding paths");
    }
  }

  // Per feature: whether it lies at an extremity of A or of B, among the
  // top quarter by mean distance to its nearest features there (thesis 5.4).
  std::vector<char> extremities() const {
    const int k = int(sides_[0].feature.size());
    std::vector<char> extreme(k, 0);
    for (const Side& side : sides_) {
      std::vector<std::pair<double, int>> spread;
      for (int f = 0; f < k; ++f) {
        if (is_centre(f)) continue;
        std::vector<double> distance;
        for (int g = 0; g < k; ++g)
          if (g != f && !is_centre(g))
            distance.push_back((side.mesh.position(side.feature[f]) - side.mesh.position(side.feature[g])).norm());
        const size_t n = std::min<size_t>(kExtremityNeighbours, distance.size());
        std::partial_sort(distance.begin(), distance.begin() + n, distance.end());
        const double sum = std::accumulate(distance.begin(), distance.begin() + n, 0.0);
        const double mean = sum / double(std::max<size_t>(n, 1));
        spread.push_back({-mean, f});  // farthest first
      }
      std::sort(spread.begin(), spread.end());
      for (size_t n = 0; n < spread.size() / 4; ++n) extreme[spread[n].second] = 1;
    }
    return extreme;
  }

  // The nearest feature of neither i's nor j's component that the two halves
  // of `traced` pass on different sides (-1: none), among the features nearest
  // i and j on each mesh.
  int wrong_side(int i, int j, const Traced& traced, UnionFind& components) const {
    const int k = int(sides_[0].feature.size());
    std::vector<std::pair<double, int>> near;
    for (int f = 0; f < k; ++f)
      if (components.find(f) != components.find(i) && components.find(f) != components.find(j) && !is_centre(f))
        near.push_back({std::min(cost(f, i), cost(f, j)), f});
    std::sort(near.begin(), near.end());
    near.resize(std::min<size_t>(near.size(), kSideNeighbours));
    if (near.empty()) return -1;
    std::vector<int> side[2];
    for (int s = 0; s < 2; ++s) {
      std::vector<int> queries;
      for (const auto& [c, f] : near) queries.push_back(sides_[s].feature[f]);
      side[s] = sides_[s].sides_of(traced.nodes[s], traced.vertices[s], queries);
    }
    for (size_t n = 0; n < near.size(); ++n)
      if (side[0][n] * side[1][n] < 0) return near[n].second;
    return -1;
  }

  // Re-traces one half of `traced` so that feature n lies on the side of it
  // the other half leaves n on (thesis 5.4): temporary paths from n to i and
  // to j (vertices only, so the mesh is unchanged) leave the new half one
  // sector at each end, the one before or after them; it still keeps to the
  // other half's sectors. Of the two halves re-traced, the shorter pair is
  // kept; false (`traced` unchanged) when neither puts n on one side.
  bool reroute(int i, int j, int n, Traced& traced) {
    Traced best;
    for (int s = 0; s < 2; ++s) {
      const int r = 1 - s;  // the reference half
      const int want = sides_[r].sides_of(traced.nodes[r], traced.vertices[r], {sides_[r].feature[n]})[0];
      Side& side = sides_[s];
      std::vector<int> arm_i = side.trace(n, i, nullptr, nullptr, false, nullptr);
      if (!want || arm_i.empty()) continue;
      std::vector<std::pair<int, char>> blocked;
      std::vector<int> closed;
      const auto close = [&](const std::vector<int>& arm) {
        for (size_t a = 0; a < arm.size(); ++a) {
          blocked.push_back({arm[a], side.blocked[arm[a]]});
          side.blocked[arm[a]] = 1;
          if (a + 1 < arm.size() && side.path_edges.insert(side.mesh.edge(arm[a], arm[a + 1])).second)
            closed.push_back(side.mesh.edge(arm[a], arm[a + 1]));
        }
      };
      close(arm_i);
      const std::vector<int> arm_j = side.trace(n, j, nullptr, nullptr, false, nullptr);
      Traced candidate = traced;
      if (!arm_j.empty()) {
        close(arm_j);
        const std::array<End, 2> used = gaps(r, i, j, traced);
        const auto cut = [&](int f, const std::vector<int>& arm, bool before) {
          const std::vector<int> ring = side.mesh.ring(side.feature[f]);
          const auto at = std::find(ring.begin(), ring.end(), arm[arm.size() - 2]);
          return Gate{true, used[f == i ? 0 : 1], double(at - ring.begin()), before};
        };
        const Side::StepFactor guide = s == 1 ? near_a(traced) : Side::StepFactor();
        candidate.nodes[s] = trace_on(s, i, j, cut(i, arm_i, want > 0), cut(j, arm_j, want < 0),
                                      s == 1 ? &guide : nullptr, candidate.vertices[s]);
      }
      for (auto it = blocked.rbegin(); it != blocked.rend(); ++it) side.blocked[it->first] = it->second;
      for (int e : closed) side.path_edges.erase(e);
      if (arm_j.empty() || candidate.nodes[s].empty() ||
          side.sides_of(candidate.nodes[s], candidate.vertices[s], {side.feature[n]})[0] != want)
        continue;
      candidate.length = length(0, candidate) + length(1, candidate);
      if (best.nodes[0].empty() || candidate.length < best.length) best = std::move(candidate);
    }
    if (best.nodes[0].empty()) return false;
    traced = std::move(best);
    return true;
  }

  // Counter-clockwise ends around every feature (on side s).
  std::vector<std::vector<End>> rotation(int s) const {
    std::vector<std::vector<End>> around(sides_[s].feature.size());
    for (int f = 0; f < int(around.size()); ++f) around[f] = sides_[s].ends(f, edges_);
    return around;
  }

  // Boundary walks of the faces of the (connected) network, from A's rotation.
  std::vector<Walk> walks() const {
    const std::vector<std::vector<End>> around = rotation(0);
    std::vector<std::vector<char>> seen(around.size());
    for (size_t f = 0; f < around.size(); ++f) seen[f].assign(around[f].size(), 0);
    std::vector<Walk> result;
    for (int f = 0; f < int(around.size()); ++f)
      for (int i = 0; i < int(around[f].size()); ++i) {
        if (seen[f][i]) continue;
        Walk walk;
        Corner c{f, i};
        while (!seen[c.feature][c.index]) {
          seen[c.feature][c.index] = 1;
          const std::vector<End>& here = around[c.feature];
          const End out = here[(c.index + 1) % here.size()];
          walk.corners.push_back(c);
          walk.after.push_back(here[c.index]);
          walk.leaving.push_back(out);
          const int g = edges_[out.path][1 - out.end];
          const std::vector<End>& there = around[g];
          const End in{out.path, 1 - out.end};
          c = {g, int(std::find(there.begin(), there.end(), in) - there.begin())};
        }
        result.push_back(walk);
      }
    return result;
  }

  void require_one_region() const {
    for (int s = 0; s < 2; ++s) {
      if (sides_[s].surface_regions() != 1)
        throw Error(std::string("internal error: a non-separating path separates ") + (s == 0 ? "A" : "B"));
    }
  }

  // Phase 2: 2g non-separating paths (the seeded holes' cycles bound their fans).
  void handles() {
    while (int(edges_.size()) - int(sides_[0].feature.size()) + 1 - seeded_cycles_ < 2 * genus_) {
      std::vector<Walk> all = walks();
      all.erase(std::remove_if(all.begin(), all.end(),
                               [&](const Walk& w) {
                                 return std::any_of(w.corners.begin(), w.corners.end(),
                                                    [&](const Corner& c) { return is_centre(c.feature); });
                               }),
                all.end());
      if (all.size() >= 2) {
        join(all);
      } else {
        handle_loop();
      }
      require_one_region();
    }
  }

  // A path between corners of two different walks: never separating.
  void join(const std::vector<Walk>& all) {
    using Named = std::pair<int, End>;  // a corner: feature and the end it follows
    std::vector<std::pair<double, std::pair<Named, Named>>> candidates;
    for (size_t i = 0; i < all[0].corners.size(); ++i)
      for (size_t w = 1; w < all.size(); ++w)
        for (size_t j = 0; j < all[w].corners.size(); ++j) {
          const Named x{all[0].corners[i].feature, all[0].after[i]}, y{all[w].corners[j].feature, all[w].after[j]};
          if (x.first != y.first) candidates.push_back({cost(x.first, y.first), {x, y}});
        }
    std::sort(candidates.begin(), candidates.end(),
              [](const auto& p, const auto& q) { return p.first < q.first; });
    for (int n = 0; n < int(candidates.size()) && n < kJoinAttempts; ++n) {
      const auto& [x, y] = candidates[n].second;
      if (connect(x.first, y.first, {Attach::kFixed, x.second}, {Attach::kFixed, y.second})) return;
    }
    throw Error("could not join two boundaries of the cut surface by corresponding paths");
  }

  // The shortest non-separating cycle found by tree-cotree in the single
  // region of side s: a vertex list from its apex back to it. On B, `on_a`
  // is A's cycle: a second cycle is found from the vertex nearest its apex
  // with lengths weighted by the distance from it (path_guide.h), and the
  // one nearer A's is kept (a copy of A keeps A's own cycle).
  std::vector<int> nonseparating_cycle(int s, const std::vector<Vec3>& on_a = {}) {
    for (int attempt = 0; attempt < 2; ++attempt) {
      Side& side = sides_[s];
      std::vector<double> far;
      std::vector<int> parent;
      std::vector<int> sources;
      for (int v = 0; v < side.mesh.vertex_count(); ++v)
        if (side.blocked[v]) sources.push_back(v);
      side.dijkstra(sources, nullptr, far, parent);
      int root = -1;
      std::vector<int> free;
      for (int v = 0; v < side.mesh.vertex_count(); ++v)
        if (!side.blocked[v] && std::isfinite(far[v])) {
          free.push_back(v);
          if (root < 0 || far[v] > far[root]) root = v;
        }
      if (root >= 0) {
        std::vector<int> cycle = tree_cotree_cycle(side, root, nullptr);
        if (!on_a.empty()) {
          const Side::StepFactor near_a = guide_.near(on_a);
          std::vector<Vec3> positions;
          for (int v : free) positions.push_back(side.mesh.position(v));
          std::vector<int> guided = tree_cotree_cycle(side, free[guide_.nearest(on_a.front(), positions)], &near_a);
          const auto remoteness = [&](const std::vector<int>& c) {
            double sum = 0;
            for (int v : c) sum += near_a(side.mesh.position(v));
            return c.empty() ? kInf : sum / double(c.size());
          };
          if (remoteness(guided) < remoteness(cycle)) cycle = std::move(guided);
        }
        if (!cycle.empty()) return cycle;
      }
      // Too thin to hold a cycle of free vertices: split the edges between path vertices and retry.
      const int edges = side.mesh.edge_count();
      for (int e = 0; e < edges; ++e) {
        const auto [u, w] = side.mesh.edge_vertices(e);
        if (u >= 0 && side.blocked[u] && side.blocked[w] && !side.path_edges.count(e) &&
            !side.fan(side.mesh.edge_faces(e)[0]))
          side.split(e);
      }
    }
    throw Error(std::string("no non-separating cycle found on ") + (s == 0 ? "A" : "B"));
  }

  // A new feature pair on a non-separating cycle of each mesh, joined to the
  // network; the cycle becomes two paths through a second new pair.
  void handle_loop() {
    std::vector<int> cycle[2];
    std::vector<Vec3> on_a;
    for (int s = 0; s < 2; ++s) {
      cycle[s] = nonseparating_cycle(s, on_a);
      Side& side = sides_[s];
      if (s == 0) {
        for (int v : cycle[0]) on_a.push_back(side.mesh.position(v));
      } else {
        // Start B's cycle (the new pair) where A's starts.
        std::vector<Vec3> positions;
        for (int v : cycle[1]) positions.push_back(side.mesh.position(v));
        const int k = guide_.nearest(on_a.front(), positions) % int(cycle[1].size() - 1);
        std::vector<int> turned(cycle[1].begin() + k, cycle[1].end() - 1);
        turned.insert(turned.end(), cycle[1].begin(), cycle[1].begin() + k + 1);
        cycle[1] = std::move(turned);
      }
      for (size_t i = 0; i + 1 < cycle[s].size(); ++i)
        side.path_edges.insert(side.mesh.edge(cycle[s][i], cycle[s][i + 1]));
      for (int v : cycle[s]) side.blocked[v] = 1;
    }
    const int p = add_pair(cycle[0].front(), cycle[1].front());
    std::vector<std::pair<double, int>> targets;
    for (int f = 0; f < p; ++f)
      if (!is_centre(f)) targets.push_back({cost(p, f), f});
    std::sort(targets.begin(), targets.end());
    bool joined = false;
    for (const auto& [c, f] : targets)
      if ((joined = connect(p, f, {Attach::kFree, {}}, {Attach::kMatch, {}}))) break;
    if (!joined) throw Error("could not join a non-separating cycle to the path network");
    // Orient B's cycle so the three ends at p have A's cyclic order.
    bool ccw[2];
    for (int s = 0; s < 2; ++s) {
      const Side& side = sides_[s];
      const std::vector<int> ring = side.mesh.ring(side.feature[p]);
      const auto pos = [&](int v) { return std::find(ring.begin(), ring.end(), v) - ring.begin(); };
      const long n = long(ring.size());
      const long join_at = pos(side.paths.back()[1]);
      const long out = (pos(cycle[s][1]) - join_at + n) % n;
      const long in = (pos(cycle[s][cycle[s].size() - 2]) - join_at + n) % n;
      ccw[s] = out < in;
    }
    if (ccw[0] != ccw[1]) std::reverse(cycle[1].begin(), cycle[1].end());
    // Split each cycle at half its length: a second new pair.
    int middle[2];
    for (int s = 0; s < 2; ++s) {
      const Side& side = sides_[s];
      double total = 0;
      std::vector<double> at{0};
      for (size_t i = 1; i < cycle[s].size(); ++i)
        at.push_back(total += (side.mesh.position(cycle[s][i]) - side.mesh.position(cycle[s][i - 1])).norm());
      middle[s] = 1;
      for (int i = 1; i + 1 < int(cycle[s].size()); ++i)
        if (std::abs(at[i] - total / 2) < std::abs(at[middle[s]] - total / 2)) middle[s] = i;
    }
    {  // B's second pair where A's lies.
      const Side& side = sides_[1];
      std::vector<Vec3> inner;
      for (size_t i = 1; i + 1 < cycle[1].size(); ++i) inner.push_back(side.mesh.position(cycle[1][i]));
      middle[1] = 1 + guide_.nearest(sides_[0].mesh.position(cycle[0][middle[0]]), inner);
    }
    const int q = add_pair(cycle[0][middle[0]], cycle[1][middle[1]]);
    for (int s = 0; s < 2; ++s) {
      Side& side = sides_[s];
      side.register_path(std::vector<int>(cycle[s].begin(), cycle[s].begin() + middle[s] + 1));
      side.register_path(std::vector<int>(cycle[s].begin() + middle[s], cycle[s].end()));
    }
    edges_.push_back({p, q});
    edges_.push_back({q, p});
  }

  // The unblocked vertex of side s in `region` farthest from its boundary
  // or, with `near` (a position on A), the one nearest it in A's frame (so
  // B's new feature lies where A's does); an edge of the region is split
  // when it has none.
  int centre(int s, const std::vector<int>& region, int r, const Vec3* near = nullptr) {
    Side& side = sides_[s];
    for (int attempt = 0; attempt < 2; ++attempt) {
      std::vector<char> inside(side.mesh.vertex_count(), 0);
      std::vector<int> sources;
      for (int f = 0; f < int(region.size()); ++f)
        if (region[f] == r)
          for (int v : side.mesh.triangles()[f]) {
            if (!inside[v] && side.blocked[v]) sources.push_back(v);
            inside[v] = 1;
          }
      std::vector<double> dist;
      std::vector<int> parent;
      side.dijkstra(sources, &inside, dist, parent);
      int best = -1;
      std::vector<int> free;
      std::vector<Vec3> positions;
      for (int v = 0; v < side.mesh.vertex_count(); ++v)
        if (inside[v] && !side.blocked[v] && std::isfinite(dist[v])) {
          free.push_back(v), positions.push_back(side.mesh.position(v));
          if (best < 0 || dist[v] > dist[best]) best = v;
        }
      if (best >= 0) return near ? free[guide_.nearest(*near, positions)] : best;
      int longest = -1;
      double length = -1;
      for (int f = 0; f < int(region.size()); ++f)
        if (region[f] == r) {
          const Triangle& t = side.mesh.triangles()[f];
          for (int k = 0; k < 3; ++k) {
            const int e = side.mesh.edge(t[k], t[(k + 1) % 3]);
            const double l = (side.mesh.position(t[k]) - side.mesh.position(t[(k + 1) % 3])).norm();
            if (!side.path_edges.count(e) && l > length) length = l, longest = e;
          }
        }
      if (longest < 0) break;
      side.split(longest);
    }
    throw Error("a face of the partition is too narrow for a new feature");
  }

  // Phase 3: a new feature pair in every face that is not a triangle of three
  // distinct features, joined to each corner of its walk in order.
  void complete() {
    const int limit = 8 * int(edges_.size()) + 64;  // each round adds a path; a face of m corners needs m - 3
    for (int round = 0;; ++round) {
      if (round > limit) throw Error("could not complete the partition to triangles");
      std::vector<Walk> todo;
      for (const Walk& w : walks()) {
        std::vector<int> f;
        for (const Corner& c : w.corners) f.push_back(c.feature);
        std::sort(f.begin(), f.end());
        if (f.size() != 3 || std::unique(f.begin(), f.end()) != f.end()) todo.push_back(w);
      }
      if (todo.empty()) return;
      for (const Walk& walk : todo) {
        if (diagonal(walk)) continue;
        const std::vector<End>& corner_ends = walk.after;
        int v[2];
        for (int s = 0; s < 2; ++s) {
          int count = 0;
          const std::vector<int> region = sides_[s].regions(count);
          const int r = region[sides_[s].corner_face(walk.corners[0].feature, corner_ends[0])];
          if (s == 0) {
            v[0] = centre(0, region, r);
          } else {
            const Vec3 on_a = sides_[0].mesh.position(v[0]);
            v[1] = centre(1, region, r, &on_a);
          }
        }
        const int c = add_pair(v[0], v[1]);
        for (size_t k = 0; k < walk.corners.size(); ++k)
          if (!connect(c, walk.corners[k].feature, {Attach::kFree, {}}, {Attach::kFixed, corner_ends[k]}))
            throw Error("could not join a new feature to the corners of its face");
      }
    }
  }

  // The shortest-looking path between two non-adjacent corners of distinct
  // features of a face, inside it: splits it into two smaller faces.
  bool diagonal(const Walk& walk) {
    const int m = int(walk.corners.size());
    std::vector<std::pair<double, std::array<int, 2>>> candidates;
    for (int i = 0; i < m; ++i)
      for (int j = i + 2; j < m; ++j) {
        if ((i + m - j) < 2 || walk.corners[i].feature == walk.corners[j].feature) continue;
        candidates.push_back({cost(walk.corners[i].feature, walk.corners[j].feature), {i, j}});
      }
    std::sort(candidates.begin(), candidates.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
    // Of the nearest few, the shortest traced pair. A pair's cost (straight
    // lines) bounds its traced length from below, so pairs that cannot beat
    // the best so far are not traced.
    Traced best;
    std::array<int, 2> chosen{-1, -1};
    for (int n = 0; n < int(candidates.size()) && n < kDiagonalAttempts; ++n) {
      if (chosen[0] >= 0 && candidates[n].first >= best.length) break;
      const auto [i, j] = candidates[n].second;
      Traced traced;
      if (trace(walk.corners[i].feature, walk.corners[j].feature, {Attach::kFixed, walk.after[i]},
                {Attach::kFixed, walk.after[j]}, traced, chosen[0] >= 0 ? best.length : kInf) &&
          (chosen[0] < 0 || traced.length < best.length)) {
        best = std::move(traced);
        chosen = {i, j};
      }
    }
    if (chosen[0] < 0) return false;
    lay(walk.corners[chosen[0]].feature, walk.corners[chosen[1]].feature, best);
    return true;
  }

  ConsistentPartition assemble() {
    // Equal rotation systems: the same cyclic order of ends at every feature.
    const auto around_a = rotation(0), around_b = rotation(1);
    for (size_t f = 0; f < around_a.size(); ++f) {
      const auto& x = around_a[f];
      const auto& y = around_b[f];
      bool same = x.size() == y.size();
      if (same && !x.empty()) {
        const size_t shift = std::find(y.begin(), y.end(), x[0]) - y.begin();
        for (size_t i = 0; same && i < x.size(); ++i) same = shift < y.size() && x[i] == y[(i + shift) % y.size()];
      }
      if (!same) throw Error("internal error: the cyclic order of paths differs at feature " + std::to_string(f));
    }
    ConsistentPartition result;
    result.edges = edges_;
    result.delayed_paths = delayed_;
    result.rerouted_paths = rerouted_;
    const std::vector<Walk> all = walks();
    const int v = int(sides_[0].feature.size()), e = int(edges_.size()), f = int(all.size());
    if (v - e + f != 2 - 2 * genus_)
      throw Error("internal error: the partition has Euler characteristic " + std::to_string(v - e + f));
    for (const Walk& w : all) {
      BaseTriangle t;
      for (int k = 0; k < 3; ++k) {
        t.corners[k] = w.corners[k].feature;
        t.edges[k] = w.leaving[k].path;
        t.reversed[k] = w.leaving[k].end == 1;
      }
      result.triangles.push_back(t);
    }
    for (int s = 0; s < 2; ++s) {
      Side& side = sides_[s];
      int count = 0;
      const std::vector<int> region = side.regions(count);
      if (count != f)
        throw Error(std::string("internal error: ") + (s == 0 ? "A" : "B") + " has " + std::to_string(count) +
                    " regions for " + std::to_string(f) + " base triangles");
      std::vector<int> triangle_of(count, -1);
      for (int t = 0; t < f; ++t) {
        int& slot = triangle_of[region[side.corner_face(all[t].corners[0].feature, all[t].after[0])]];
        if (slot >= 0) throw Error("internal error: two base triangles share a region");
        slot = t;
      }
      PartitionSide out{std::move(side.mesh), side.first_fan, side.feature, side.paths, {}};
      for (int r : region) out.patch.push_back(triangle_of[r]);
      result.sides.push_back(std::move(out));
    }
    return result;
  }

  int genus_;
  PathGuide guide_;
  const PartitionHoles& holes_;
  std::vector<int> centres_;  // features at hole centres
  int seeded_cycles_ = 0;
  int delayed_ = 0, rerouted_ = 0;
  std::vector<Side> sides_;
  double scale_[2] = {1, 1};
  std::vector<std::array<int, 2>> edges_;
};

}  // namespace

ConsistentPartition consistent_partition(const TriangleMesh& a, const TriangleMesh& b,
                                         const std::vector<std::array<int, 2>>& features, int genus,
                                         const PartitionHoles& holes) {
  if (features.empty()) throw InvalidInput("a consistent partition needs at least one feature pair");
  Partitioner partitioner(a, b, features, genus, holes);
  ConsistentPartition result = partitioner.run();
  result.given_features = int(features.size());
  return result;
}

}  // namespace cmaps
