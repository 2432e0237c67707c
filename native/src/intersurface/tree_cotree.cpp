#include "intersurface/tree_cotree.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

namespace cmaps::partition {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

std::vector<int> tree_cotree_cycle(const Side& side, int root, const Side::StepFactor* factor) {
  std::vector<double> weight;
  if (factor)
    for (int v = 0; v < side.mesh.vertex_count(); ++v) weight.push_back((*factor)(side.mesh.position(v)));
  const std::vector<double>* weights = factor ? &weight : nullptr;
  std::vector<int> parent;
  std::vector<double> dist;
  side.dijkstra({root}, nullptr, dist, parent, weights);
  const int edges = side.mesh.edge_count();
  std::vector<char> tree(edges, 0), cotree(edges, 0);
  for (int v = 0; v < side.mesh.vertex_count(); ++v)
    if (parent[v] >= 0) tree[side.mesh.edge(v, parent[v])] = 1;
  // Cotree: a maximum spanning tree of the faces across non-path,
  // non-tree edges, weighted by the length of the loop each edge closes
  // with the tree (Erickson & Whittlesey 2005): the edges left over then
  // close the shortest loops, among them the shortest non-separating one
  // through the root. Edges at a path vertex close no usable loop and go
  // into the cotree first.
  const int faces = int(side.mesh.triangles().size());
  std::vector<int> group(faces);
  std::iota(group.begin(), group.end(), 0);
  const std::function<int(int)> find = [&](int x) {
    while (group[x] != x) x = group[x] = group[group[x]];
    return x;
  };
  std::vector<std::pair<double, int>> order;
  for (int e = 0; e < edges; ++e) {
    const auto [u, w] = side.mesh.edge_vertices(e);
    if (u < 0 || tree[e] || side.path_edges.count(e)) continue;
    const bool usable = !side.blocked[u] && !side.blocked[w] && std::isfinite(dist[u]) && std::isfinite(dist[w]);
    order.push_back({usable ? dist[u] + dist[w] + side.step(u, w, weights) : kInf, e});
  }
  std::sort(order.begin(), order.end(), std::greater<>());
  for (const auto& [length, e] : order) {
    const auto& two = side.mesh.edge_faces(e);
    const int x = find(two[0]), y = find(two[1]);
    if (x != y) {
      group[x] = y;
      cotree[e] = 1;
    }
  }
  std::vector<int> depth(side.mesh.vertex_count(), -1);
  const auto depth_of = [&](int v) {
    std::vector<int> chain;
    for (int u = v; depth[u] < 0; u = parent[u]) {
      chain.push_back(u);
      if (parent[u] < 0) {
        depth[u] = 0;
        chain.pop_back();
        break;
      }
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) depth[*it] = depth[parent[*it]] + 1;
    return depth[v];
  };
  const auto lca = [&](int u, int w) {
    while (depth_of(u) > depth_of(w)) u = parent[u];
    while (depth_of(w) > depth_of(u)) w = parent[w];
    while (u != w) u = parent[u], w = parent[w];
    return u;
  };
  double best = kInf;
  int bu = -1, bw = -1;
  for (int e = 0; e < edges; ++e) {
    const auto [u, w] = side.mesh.edge_vertices(e);
    if (u < 0 || tree[e] || cotree[e] || side.path_edges.count(e) || side.blocked[u] || side.blocked[w]) continue;
    if (!std::isfinite(dist[u]) || !std::isfinite(dist[w])) continue;
    const double length =
        dist[u] + dist[w] + side.step(u, w, weights) - 2 * dist[lca(u, w)];
    if (length < best) best = length, bu = u, bw = w;
  }
  if (bu >= 0) {
    const int apex = lca(bu, bw);
    std::vector<int> cycle, back;
    for (int v = bu; v != apex; v = parent[v]) cycle.push_back(v);
    cycle.push_back(apex);
    std::reverse(cycle.begin(), cycle.end());
    for (int v = bw; v != apex; v = parent[v]) back.push_back(v);
    cycle.insert(cycle.end(), back.begin(), back.end());
    cycle.push_back(apex);
    return cycle;
  }
  return {};
}

}  // namespace cmaps::partition
