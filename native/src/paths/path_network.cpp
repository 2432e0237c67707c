#include "paths/path_network.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include "common/ring.h"
#include "consistent_maps/errors.h"
#include "paths/layout_flips.h"
#include "paths/mesh_search.h"

namespace cmaps {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSteinerPenalty = 1.0;  // a step through an edge midpoint costs 1 + this times its length
constexpr double kPenalty = 1e9;         // ranks a candidate behind every unpenalized one
const double kThinAngle = 10 * M_PI / 180;

// Counter-clockwise neighbours of v in a triangle list.
std::vector<int> ring_in(const std::vector<Triangle>& triangles, int v) {
  std::vector<Triangle> star;
  for (const Triangle& t : triangles)
    if (t[0] == v || t[1] == v || t[2] == v) star.push_back(t);
  return ring_around(v, star);
}

// The angle at a of the spherical triangle (a, b, c).
double spherical_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 tb = (b - a * a.dot(b)).normalized(), tc = (c - a * a.dot(c)).normalized();
  return std::acos(std::clamp(tb.dot(tc), -1.0, 1.0));
}

class Tracer {
 public:
  Tracer(EditableMesh& mesh, const std::vector<int>& features, const std::vector<Vec3>& targets,
         const std::vector<Triangle>& sphere_triangles)
      : mesh_(mesh), features_(features), targets_(targets) {
    const int k = static_cast<int>(features.size());
    std::map<std::pair<int, int>, int> arc_index;
    for (const Triangle& t : sphere_triangles)
      for (int i = 0; i < 3; ++i) {
        const auto key = std::minmax(t[i], t[(i + 1) % 3]);
        if (arc_index.emplace(key, static_cast<int>(network_.arcs.size())).second)
          network_.arcs.push_back({key.first, key.second});
      }
    network_.paths.resize(network_.arcs.size());
    hull_ring_.resize(k);
    for (int f = 0; f < k; ++f) hull_ring_[f] = ring_in(sphere_triangles, f);
    // Arcs of thin spherical triangles go last: their winding is unreliable.
    thin_.assign(network_.arcs.size(), 0);
    for (const Triangle& t : sphere_triangles) {
      double smallest = kInf;
      for (int i = 0; i < 3; ++i)
        smallest = std::min(smallest, spherical_angle(targets[t[i]], targets[t[(i + 1) % 3]], targets[t[(i + 2) % 3]]));
      if (smallest < kThinAngle)
        for (int i = 0; i < 3; ++i) thin_[arc_index.at(std::minmax(t[i], t[(i + 1) % 3]))] = 1;
    }
    first_step_.resize(k);
    blocked_.assign(mesh.vertex_count(), 0);
    for (int v : features) blocked_[v] = 1;
    component_.resize(k);
    std::iota(component_.begin(), component_.end(), 0);
    components_ = k;
    done_.assign(network_.arcs.size(), 0);
    extremity_.assign(k, 0);
  }

  // Lays down a given path between two features' vertices.
  void prelay(const std::vector<int>& path) {
    std::unordered_map<int, int> feature_of;
    for (int f = 0; f < static_cast<int>(features_.size()); ++f) feature_of[features_[f]] = f;
    if (path.size() < 2 || !feature_of.count(path.front()) || !feature_of.count(path.back()))
      throw Error("internal error: a given path does not join two features");
    int i = feature_of.at(path.front()), j = feature_of.at(path.back());
    std::vector<int> nodes = path;
    if (i > j) {
      std::swap(i, j);
      std::reverse(nodes.begin(), nodes.end());
    }
    int a = -1;
    for (int b = 0; b < static_cast<int>(network_.arcs.size()); ++b)
      if (network_.arcs[b][0] == i && network_.arcs[b][1] == j) a = b;
    if (a < 0) throw Error("internal error: a given path is not an arc of the layout");
    if (done_[a]) throw Error("internal error: two given paths for one arc");
    for (size_t s = 0; s + 1 < nodes.size(); ++s)
      if (mesh_.edge(nodes[s], nodes[s + 1]) < 0) throw Error("internal error: a given path is not along mesh edges");
    search_vertices_ = mesh_.vertex_count();
    lay_down(a, nodes);
    done_[a] = 1;
    ++prelaid_;
  }

  PathNetwork run(const ProgressSlice& progress) {
    const int arcs = static_cast<int>(network_.arcs.size());
    length_.assign(arcs, kInf);
    for (int a = 0; a < arcs; ++a) length_[a] = path_length(trace(a, false, false));
    for (int a = 0; a < arcs; ++a)
      if (done_[a]) length_[a] = path_length(network_.paths[a]);
    find_extremities();

    // Union-find over features: the tree phase only links different components.
    std::vector<char>& done = done_;
    for (int traced = prelaid_; traced < arcs;) {
      const bool tree_phase = components_ > 1;
      int best = -1, runner_up = -1;
      for (int a = 0; a < arcs; ++a) {
        if (done[a] || (tree_phase && root(network_.arcs[a][0]) == root(network_.arcs[a][1]))) continue;
        if (best < 0 || rank(a) < rank(best)) {
          runner_up = best;
          best = a;
        } else if (runner_up < 0 || rank(a) < rank(runner_up)) {
          runner_up = a;
        }
      }
      if (best < 0) throw Error("internal error: path network has no candidate left");
      // Re-trace in the current network; keep it if it is still the best.
      std::vector<int> nodes = trace(best, true, false);
      if (nodes.empty()) nodes = trace(best, true, true);
      const double length = path_length(nodes);
      if (length > length_[best] * (1 + 1e-9) && runner_up >= 0 && std::isfinite(length_[best])) {
        length_[best] = length;
        ++network_.retraced;
        if (rank(best) > rank(runner_up)) continue;
      }
      if (nodes.empty()) {
        if (failures_++ > 4 * arcs) throw Error("could not trace a path network for these features and targets");
        length_[best] = kInf;
        continue;
      }
      lay_down(best, nodes);
      done[best] = 1;
      ++traced;
      progress.report(double(traced) / arcs);
    }
    return std::move(network_);
  }

 private:
  int root(int f) {
    while (component_[f] != f) f = component_[f] = component_[component_[f]];
    return f;
  }

  // Lower is better: the path length, behind every other candidate when the
  // arc belongs to a thin spherical triangle, or when it links two ordinary
  // features while some extremity is still unconnected (thesis 3.3.3).
  double rank(int a) const {
    double r = length_[a];
    if (thin_[a]) r += kPenalty;
    const auto [i, j] = network_.arcs[a];
    if (!extremity_[i] && !extremity_[j] && unconnected_extremities_ > 0) r += kPenalty;
    return r;
  }

  // Extremities (legs, arms, ...) have a large mean distance to their neighbours.
  void find_extremities() {
    const int k = static_cast<int>(features_.size());
    std::vector<double> mean(k, 0);
    std::vector<int> count(k, 0);
    for (size_t a = 0; a < network_.arcs.size(); ++a)
      if (std::isfinite(length_[a]))
        for (int f : network_.arcs[a]) {
          mean[f] += length_[a];
          ++count[f];
        }
    for (int f = 0; f < k; ++f) mean[f] = count[f] ? mean[f] / count[f] : 0;
    std::vector<double> sorted = mean;
    std::nth_element(sorted.begin(), sorted.begin() + k / 2, sorted.end());
    const double median = sorted[k / 2];
    extremity_.assign(k, 0);
    for (int f = 0; f < k; ++f)
      if (mean[f] > 1.5 * median && first_step_[f].empty()) {
        extremity_[f] = 1;
        ++unconnected_extremities_;
      }
  }

  // The sector of feature f through which the path of arc a must leave.
  Sector sector(int f, int a, int vertices, bool midpoints) const {
    Sector s;
    const int v = features_[f];
    const std::vector<int> ring = mesh_.ring(v);
    s.size = static_cast<double>(ring.size());
    for (size_t k = 0; k < ring.size(); ++k) {
      s.position[ring[k]] = static_cast<double>(k);
      if (midpoints) {
        s.position[vertices + mesh_.edge(ring[k], ring[(k + 1) % ring.size()])] = k + 0.5;
        // The midpoint of the edge to ring vertex k replaces it once split.
        s.position[vertices + mesh_.edge(v, ring[k])] = static_cast<double>(k);
      }
    }
    const auto& around = hull_ring_[f];
    const int other = network_.arcs[a][0] == f ? network_.arcs[a][1] : network_.arcs[a][0];
    const int q = static_cast<int>(std::find(around.begin(), around.end(), other) - around.begin());
    const int n = static_cast<int>(around.size());
    int prev = -1, next = -1;
    for (int step = 1; step < n && prev < 0; ++step) {
      const auto it = first_step_[f].find(around[(q - step + n) % n]);
      if (it != first_step_[f].end()) prev = it->second;
    }
    for (int step = 1; step < n && next < 0; ++step) {
      const auto it = first_step_[f].find(around[(q + step) % n]);
      if (it != first_step_[f].end()) next = it->second;
    }
    if (prev < 0) return s;  // no path at f yet
    s.everything = false;
    s.lo = s.position.at(prev);
    s.span = prev == next ? s.size : std::fmod(s.position.at(next) - s.lo + s.size, s.size);
    return s;
  }

  // A* from arc a's first feature to its second over mesh vertices (and edge
  // midpoints when allowed), avoiding laid paths; with `restricted`, leaving
  // and entering the features only through their sectors.
  std::vector<int> trace(int a, bool restricted, bool midpoints) {
    const int vertices = mesh_.vertex_count();
    search_vertices_ = vertices;
    SearchRules rules;
    rules.blocked = &blocked_;
    rules.closed_edges = &path_edges_;
    rules.midpoints = midpoints;
    rules.midpoint_penalty = kSteinerPenalty;
    Sector from, to;
    if (restricted) {
      from = sector(network_.arcs[a][0], a, vertices, midpoints);
      to = sector(network_.arcs[a][1], a, vertices, midpoints);
      rules.leave = &from;
      rules.enter = &to;
    }
    return shortest_path(mesh_, features_[network_.arcs[a][0]], features_[network_.arcs[a][1]], rules);
  }

  double path_length(const std::vector<int>& nodes) const { return cmaps::path_length(mesh_, nodes, search_vertices_); }


  // Turns a traced node sequence into mesh vertices (splitting the edges of
  // midpoint nodes) and blocks it for later paths.
  void lay_down(int a, const std::vector<int>& nodes) {
    const int vertices = search_vertices_;
    std::vector<int> path;
    for (int node : nodes) {
      if (node < vertices) {
        path.push_back(node);
      } else {
        path.push_back(mesh_.split_edge(node - vertices));
        ++network_.steiner_vertices;
        blocked_.push_back(0);
      }
    }
    path = reconnect_traced_path(mesh_, path, vertices);
    for (size_t i = 0; i + 1 < path.size(); ++i) path_edges_.insert(mesh_.edge(path[i], path[i + 1]));
    for (size_t i = 1; i + 1 < path.size(); ++i) blocked_[path[i]] = 1;
    const auto [i, j] = network_.arcs[a];
    first_step_[i][j] = path[1];
    first_step_[j][i] = path[path.size() - 2];
    for (int f : {i, j})
      if (extremity_[f] && first_step_[f].size() == 1) --unconnected_extremities_;
    if (root(i) != root(j)) --components_;
    component_[root(i)] = root(j);
    network_.paths[a] = std::move(path);
  }

  EditableMesh& mesh_;
  const std::vector<int>& features_;
  const std::vector<Vec3>& targets_;
  PathNetwork network_;
  std::vector<std::vector<int>> hull_ring_;
  std::vector<char> thin_, extremity_, blocked_;
  std::vector<double> length_;
  std::vector<int> component_;
  std::vector<std::unordered_map<int, int>> first_step_;  // feature -> (neighbour feature -> first path vertex)
  EdgeSet path_edges_;
  int unconnected_extremities_ = 0;
  int components_ = 0, prelaid_ = 0;
  std::vector<char> done_;
  int search_vertices_ = 0;
  int failures_ = 0;
};

}  // namespace

PathNetwork trace_path_network(EditableMesh& mesh, const std::vector<int>& features, const std::vector<Vec3>& targets,
                               const std::vector<Triangle>& sphere_triangles, const ProgressSlice& progress,
                               const std::vector<std::vector<int>>& prelaid) {
  std::vector<Triangle> layout = sphere_triangles;
  std::vector<std::array<int, 2>> fixed;
  if (!prelaid.empty()) {
    std::unordered_map<int, int> feature_of;
    for (int f = 0; f < static_cast<int>(features.size()); ++f) feature_of[features[f]] = f;
    for (const auto& path : prelaid)
      if (feature_of.count(path.front()) && feature_of.count(path.back()))
        fixed.push_back({feature_of.at(path.front()), feature_of.at(path.back())});
  }
  const int flips = flip_layout_to_shorter_paths(mesh, features, targets, layout, fixed);
  Tracer tracer(mesh, features, targets, layout);
  for (const auto& path : prelaid) tracer.prelay(path);
  PathNetwork network = tracer.run(progress);
  network.flips = flips;
  return network;
}

}  // namespace cmaps
