#include "intersurface/partition_network.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>
#include <unordered_set>

#include "consistent_maps/errors.h"

namespace cmaps::partition {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMidpointPenalty = 1.0;  // a step through an edge midpoint costs 1 + this times its length

// Ring positions of v's search neighbours (see Side::positions).
Sector ring_positions(const EditableMesh& mesh, int v, int vertices, bool midpoints) {
  Sector s;
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
  return ring_positions(mesh, feature[f], vertices, midpoints);
}

std::vector<int> Side::sides_of(const std::vector<int>& nodes, int vertices, const std::vector<int>& queries) const {
  const int n = mesh.vertex_count();
  std::vector<char> on_path(n, 0);
  std::unordered_set<int> crossed;  // edges the path crosses at their midpoints
  for (int node : nodes) node < vertices ? void(on_path[node] = 1) : void(crossed.insert(node - vertices));
  std::vector<double> dist(n, kInf);
  std::vector<int> side(n, 0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const auto seed = [&](int v, int s, const Vec3& at) {
    const double d = (mesh.position(v) - at).norm();
    if (on_path[v] || d >= dist[v]) return;
    dist[v] = d, side[v] = s;
    open.push({d, v});
  };
  // The vertices beside each interior node: around a vertex, its ring left
  // (counter-clockwise from the way out to the way in) or right of the path;
  // at a crossed edge, its two ends by the turn they make with the path.
  // Routes meeting the path at an end find no side.
  for (size_t k : {size_t(0), nodes.size() - 1})
    for (int u : mesh.ring(nodes[k])) seed(u, 0, mesh.position(nodes[k]));
  for (size_t k = 1; k + 1 < nodes.size(); ++k) {
    const Vec3 at = node_position(mesh, nodes[k], vertices);
    if (nodes[k] < vertices) {
      const int v = nodes[k];
      const Sector around = ring_positions(mesh, v, vertices, true);
      const std::vector<int> ring = mesh.ring(v);
      const double size = around.size, out = around.position.at(nodes[k + 1]), in = around.position.at(nodes[k - 1]);
      const double left = std::fmod(in - out + size, size);
      for (int r = 0; r < int(ring.size()); ++r) {
        const double turn = std::fmod(r - out + size, size);
        if (turn > 0 && turn != left) seed(ring[r], turn < left ? 1 : -1, at);
      }
    } else {
      const int e = nodes[k] - vertices;
      const Vec3 along = node_position(mesh, nodes[k + 1], vertices) - node_position(mesh, nodes[k - 1], vertices);
      Vec3 normal = Vec3::Zero();
      for (int f : mesh.edge_faces(e)) {
        const Triangle& t = mesh.triangles()[f];
        normal += (mesh.position(t[1]) - mesh.position(t[0])).cross(mesh.position(t[2]) - mesh.position(t[0]));
      }
      for (int u : mesh.edge_vertices(e)) seed(u, normal.dot(along.cross(mesh.position(u) - at)) > 0 ? 1 : -1, at);
    }
  }
  std::unordered_map<int, int> waiting;  // query vertex -> how often asked
  for (int q : queries) ++waiting[q];
  size_t unsettled = waiting.size();
  while (!open.empty() && unsettled > 0) {
    const auto [d, u] = open.top();
    open.pop();
    if (d > dist[u]) continue;
    if (waiting.count(u) && waiting[u] > 0) waiting[u] = 0, --unsettled;
    for (int w : mesh.ring(u)) {
      if (on_path[w] || (!crossed.empty() && crossed.count(mesh.edge(u, w)))) continue;
      const double nd = d + (mesh.position(w) - mesh.position(u)).norm();
      if (nd < dist[w]) {
        dist[w] = nd, side[w] = side[u];
        open.push({nd, w});
      }
    }
  }
  std::vector<int> result;
  for (int q : queries) result.push_back(waiting.at(q) == 0 ? side[q] : 0);
  return result;
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
      for (int e : mesh.face_edges(f)) {
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
