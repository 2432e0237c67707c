#include "intersurface/partition_network.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

#include "consistent_maps/errors.h"

namespace cmaps::partition {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMidpointPenalty = 1.0;  // a step through an edge midpoint costs 1 + this times its length

}  // namespace

int Side::surface_regions() const {
  int count = 0;
  const std::vector<int> region = regions(count);
  std::vector<char> surface(count, 0);
  for (int f = 0; f < int(region.size()); ++f)
    if (!fan(f)) surface[region[f]] = 1;
  return int(std::count(surface.begin(), surface.end(), 1));
}

void Side::add_feature(int v) {
  feature.push_back(v);
  blocked[v] = 1;
}

int Side::split(int e) {
  const int m = mesh.split_edge(e);
  blocked.push_back(0);
  return m;
}

int Side::first_step(const End& x) const {
  const std::vector<int>& p = paths[x.path];
  return x.end == 0 ? p[1] : p[p.size() - 2];
}

std::vector<End> Side::ends(int f, const std::vector<std::array<int, 2>>& edges) const {
  const std::vector<int> ring = mesh.ring(feature[f]);
  std::unordered_map<int, int> at;
  for (int k = 0; k < int(ring.size()); ++k) at[ring[k]] = k;
  std::vector<std::pair<int, End>> found;
  for (int p = 0; p < int(edges.size()); ++p)
    for (int e = 0; e < 2; ++e)
      if (edges[p][e] == f) found.push_back({at.at(first_step({p, e})), End{p, e}});
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<End> result;
  for (const auto& item : found) result.push_back(item.second);
  return result;
}

Sector Side::positions(int f, int vertices, bool midpoints) const {
  Sector s;
  const int v = feature[f];
  const std::vector<int> ring = mesh.ring(v);
  s.size = double(ring.size());
  for (int k = 0; k < int(ring.size()); ++k) {
    s.position[ring[k]] = k;
    if (midpoints) {
      s.position[vertices + mesh.edge(ring[k], ring[(k + 1) % ring.size()])] = k + 0.5;
      s.position[vertices + mesh.edge(v, ring[k])] = k;
    }
  }
  return s;
}

Sector Side::after(int f, const End& x, const std::vector<End>& around, int vertices, bool midpoints) const {
  Sector s = positions(f, vertices, midpoints);
  if (x.path < 0 || around.empty()) return s;
  const int i = int(std::find(around.begin(), around.end(), x) - around.begin());
  if (i == int(around.size())) throw Error("internal error: end not found around its feature");
  const std::vector<int> ring = mesh.ring(feature[f]);
  const auto pos = [&](const End& e) {
    return double(std::find(ring.begin(), ring.end(), first_step(e)) - ring.begin());
  };
  s.everything = false;
  s.lo = pos(x);
  s.span = around.size() == 1 ? s.size : std::fmod(pos(around[(i + 1) % around.size()]) - s.lo + s.size, s.size);
  return s;
}

End Side::gap_of(int f, int node, const std::vector<End>& around, int vertices, bool midpoints) const {
  if (around.empty()) return {};
  const Sector s = positions(f, vertices, midpoints);
  const std::vector<int> ring = mesh.ring(feature[f]);
  const double q = s.position.at(node);
  End best = around.back();
  for (const End& e : around)
    if (double(std::find(ring.begin(), ring.end(), first_step(e)) - ring.begin()) < q) best = e;
  return best;
}

std::vector<int> Side::trace(int from, int to, const Sector* leave, const Sector* enter, bool midpoints,
                             const StepFactor* factor) const {
  SearchRules rules;
  rules.step_factor = factor;
  rules.blocked = &blocked;
  rules.closed_edges = &path_edges;
  rules.leave = leave;
  rules.enter = enter;
  rules.midpoints = midpoints;
  rules.midpoint_penalty = kMidpointPenalty;
  return shortest_path(mesh, feature[from], feature[to], rules);
}

double Side::step(int u, int w, const std::vector<double>* weight) const {
  const double length = (mesh.position(w) - mesh.position(u)).norm();
  return weight ? length * 0.5 * ((*weight)[u] + (*weight)[w]) : length;
}

void Side::lay(const std::vector<int>& nodes, int vertices) {
  std::vector<int> path;
  for (int node : nodes) path.push_back(node < vertices ? node : split(node - vertices));
  register_path(reconnect_traced_path(mesh, path, vertices));
}

void Side::register_path(const std::vector<int>& path) {
  for (size_t i = 0; i + 1 < path.size(); ++i) path_edges.insert(mesh.edge(path[i], path[i + 1]));
  for (int v : path) blocked[v] = 1;
  paths.push_back(path);
}

std::vector<int> Side::regions(int& count) const {
  const int faces = int(mesh.triangles().size());
  std::vector<int> region(faces, -1);
  count = 0;
  for (int seed = 0; seed < faces; ++seed) {
    if (region[seed] >= 0) continue;
    std::vector<int> stack{seed};
    region[seed] = count;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      const Triangle& t = mesh.triangles()[f];
      for (int k = 0; k < 3; ++k) {
        const int e = mesh.edge(t[k], t[(k + 1) % 3]);
        if (path_edges.count(e)) continue;
        const auto& two = mesh.edge_faces(e);
        const int g = two[0] == f ? two[1] : two[0];
        if (region[g] < 0) {
          region[g] = count;
          stack.push_back(g);
        }
      }
    }
    ++count;
  }
  return region;
}

int Side::corner_face(int f, const End& x) const {
  const int v = feature[f];
  if (x.path < 0) return mesh.faces_of(v).front();
  const std::vector<int> ring = mesh.ring(v);
  const int k = int(std::find(ring.begin(), ring.end(), first_step(x)) - ring.begin());
  const int b = ring[k], c = ring[(k + 1) % ring.size()];
  for (int t : mesh.faces_of(v)) {
    const Triangle& tri = mesh.triangles()[t];
    if (std::count(tri.begin(), tri.end(), b) && std::count(tri.begin(), tri.end(), c)) return t;
  }
  throw Error("internal error: no triangle in a corner");
}

void Side::dijkstra(const std::vector<int>& sources, const std::vector<char>* allowed, std::vector<double>& dist,
                    std::vector<int>& parent, const std::vector<double>* weight) const {
  const int n = mesh.vertex_count();
  dist.assign(n, kInf);
  parent.assign(n, -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  for (int s : sources) {
    dist[s] = 0;
    open.push({0, s});
  }
  while (!open.empty()) {
    const auto [d, u] = open.top();
    open.pop();
    if (d > dist[u]) continue;
    for (int w : mesh.ring(u)) {
      if (blocked[w] || (allowed && !(*allowed)[w])) continue;
      const double nd = d + step(u, w, weight);
      if (nd < dist[w]) {
        dist[w] = nd;
        parent[w] = u;
        open.push({nd, w});
      }
    }
  }
}

}  // namespace cmaps::partition
