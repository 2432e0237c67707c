#include "paths/mesh_search.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include "consistent_maps/errors.h"

namespace cmaps {

bool Sector::allows(int node) const {
  const auto it = position.find(node);
  if (it == position.end()) return false;
  if (everything) return true;
  const double rel = std::fmod(it->second - lo + size, size);
  return rel > 0 && rel < span;
}

Vec3 node_position(const EditableMesh& mesh, int node, int vertices) {
  if (node < vertices) return mesh.position(node);
  const auto& e = mesh.edge_vertices(node - vertices);
  return 0.5 * (mesh.position(e[0]) + mesh.position(e[1]));
}

double path_length(const EditableMesh& mesh, const std::vector<int>& nodes, int vertices) {
  if (nodes.empty()) return std::numeric_limits<double>::infinity();
  double length = 0;
  for (size_t i = 1; i < nodes.size(); ++i)
    length += (node_position(mesh, nodes[i], vertices) - node_position(mesh, nodes[i - 1], vertices)).norm();
  return length;
}

namespace {

// A search's per-node state, kept between the searches of a thread: a
// search expands a small part of a large mesh (feline - teapot: 21,000 of
// some 100,000 nodes on average), so fresh arrays for all nodes would be
// filled mostly for nothing. A node's fields lie together: the search waits
// on memory more than on arithmetic, and reads them together.
struct SearchNode {
  double cost = std::numeric_limits<double>::infinity();  // infinity: not reached
  double factor = 0;                                       // the step factor, once (0: not yet)
  int parent = -1;
  bool closed = false;
};

// The calling thread's nodes for one search, given back to their initial
// state as it ends (so a search must not start another from its step factor).
class SearchScope {
 public:
  explicit SearchScope(int nodes) : state_(shared()) {
    if (int(state_.nodes.size()) < nodes) state_.nodes.resize(nodes);
  }
  ~SearchScope() {
    for (int n : state_.touched) state_.nodes[n] = SearchNode();
    state_.touched.clear();
  }
  std::vector<SearchNode>& nodes() { return state_.nodes; }
  // Records a node about to change (some are recorded twice).
  void touch(int node) { state_.touched.push_back(node); }

 private:
  struct State {
    std::vector<SearchNode> nodes;
    std::vector<int> touched;
  };
  static State& shared() {
    thread_local State state;
    return state;
  }
  State& state_;
};

}  // namespace

std::vector<int> shortest_path(const EditableMesh& mesh, int source, int target, const SearchRules& rules) {
  const int vertices = mesh.vertex_count();
  const int nodes = vertices + (rules.midpoints ? mesh.edge_count() : 0);
  SearchScope scope(nodes);
  std::vector<SearchNode>& node = scope.nodes();
  // A node's state changes first with its cost or its factor.
  const auto reach = [&](int n, double cost) {
    if (node[n].cost == std::numeric_limits<double>::infinity()) scope.touch(n);
    node[n].cost = cost;
  };
  const Vec3 goal = mesh.position(target);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  reach(source, 0);
  open.push({(mesh.position(source) - goal).norm(), source});

  const auto factor_at = [&](int n, const Vec3& p) {
    double& f = node[n].factor;
    if (f > 0) return f;
    scope.touch(n);
    return f = (*rules.step_factor)(p);
  };

  // pu: u's position, computed once per expansion.
  auto relax = [&](int u, const Vec3& pu, int w) {
    if (w == source || node[w].closed) return;
    if (w == target) {
      if (rules.enter && !rules.enter->allows(u)) return;
    } else if (w < vertices) {
      if (rules.blocked && (*rules.blocked)[w]) return;
    } else if (rules.closed_edges && rules.closed_edges->count(w - vertices)) {
      return;
    }
    if (u == source && rules.leave && !rules.leave->allows(w)) return;
    const Vec3 pw = node_position(mesh, w, vertices);
    double step = (pw - pu).norm();
    if (u >= vertices || w >= vertices) step *= 1 + rules.midpoint_penalty;
    if (rules.step_factor) step *= 0.5 * (factor_at(u, pu) + factor_at(w, pw));
    if (node[u].cost + step < node[w].cost) {
      reach(w, node[u].cost + step);
      node[w].parent = u;
      open.push({node[w].cost + (pw - goal).norm(), w});
    }
  };

  while (!open.empty()) {
    const int u = open.top().second;
    open.pop();
    if (node[u].closed) continue;
    node[u].closed = true;
    if (u == target) break;
    const Vec3 pu = node_position(mesh, u, vertices);
    if (u < vertices) {
      // A vertex reaches its ring and the midpoints of the opposite edges.
      for (int f : mesh.faces_of(u)) {
        const Triangle& t = mesh.triangles()[f];
        const int k = t[0] == u ? 0 : t[1] == u ? 1 : 2;
        const int b = t[(k + 1) % 3], c = t[(k + 2) % 3];
        relax(u, pu, b);
        relax(u, pu, c);
        if (rules.midpoints) relax(u, pu, vertices + mesh.face_edges(f)[(k + 1) % 3]);
      }
    } else {
      // A midpoint reaches its edge's ends (once split, the halves are edges;
      // without them a path could only turn back through the triangle it
      // came from), the opposite vertices and the other edges' midpoints.
      const int e = u - vertices;
      const auto [x, y] = mesh.edge_vertices(e);
      relax(u, pu, x);
      relax(u, pu, y);
      for (int f : mesh.edge_faces(e)) {
        const Triangle& t = mesh.triangles()[f];
        const int k = t[0] != x && t[0] != y ? 0 : t[1] != x && t[1] != y ? 1 : 2;
        relax(u, pu, t[k]);
        if (rules.midpoints) {  // the two edges at the opposite corner c = t[k]
          relax(u, pu, vertices + mesh.face_edges(f)[k]);
          relax(u, pu, vertices + mesh.face_edges(f)[(k + 2) % 3]);
        }
      }
    }
  }
  if (!node[target].closed) return {};
  std::vector<int> path;
  for (int n = target; n >= 0; n = node[n].parent) path.push_back(n);
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<int> reconnect_traced_path(const EditableMesh& mesh, const std::vector<int>& path, int first_new) {
  std::vector<int> result{path.front()};
  for (size_t i = 1; i < path.size(); ++i) {
    const int from = result.back(), to = path[i];
    if (mesh.edge(from, to) < 0) {
      std::unordered_map<int, int> parent{{from, from}};
      std::vector<int> frontier{from};
      for (size_t f = 0; f < frontier.size() && !parent.count(to); ++f)
        for (int w : mesh.ring(frontier[f]))
          if ((w >= first_new || w == to) && parent.emplace(w, frontier[f]).second) frontier.push_back(w);
      if (!parent.count(to)) throw Error("internal error: traced path is not connected");
      std::vector<int> bridge;
      for (int w = parent.at(to); w != from; w = parent.at(w)) bridge.push_back(w);
      result.insert(result.end(), bridge.rbegin(), bridge.rend());
    }
    result.push_back(to);
  }
  // Cut loops: keep the part after the last visit of a repeated vertex.
  std::vector<int> simple;
  std::unordered_map<int, size_t> at;
  for (int v : result) {
    const auto it = at.find(v);
    if (it != at.end()) {
      for (size_t j = it->second + 1; j < simple.size(); ++j) at.erase(simple[j]);
      simple.resize(it->second + 1);
      continue;
    }
    at[v] = simple.size();
    simple.push_back(v);
  }
  return simple;
}

}  // namespace cmaps
