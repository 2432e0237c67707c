// Mesh validation in O(n log n): every adjacency question is answered by
// sorting halfedges by their undirected edge and by union-find, so meshes of
// 100k+ faces check in milliseconds.
#include "consistent_maps/mesh_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>

#include "consistent_maps/errors.h"
#include "mesh/union_find.h"

namespace cmaps {
namespace {

// The report plus one example of each defect, for error messages.
struct Analysis {
  MeshReport report;
  int first_non_finite = -1;
  int out_of_range_triangle = -1, out_of_range_vertex = 0;
  int repeated_index_triangle = -1;
  int first_unreferenced = -1;
  int duplicate_triangle = -1, duplicate_of = -1;
  int non_manifold_edge[2] = {-1, -1}, non_manifold_edge_faces = 0;
  int first_non_manifold_vertex = -1;
  int inconsistent_edge[2] = {-1, -1};
};

struct Halfedge {
  std::int64_t key;  // undirected edge: lo * n + hi
  int face;
  bool forward;  // traversed lo -> hi
};

bool has_repeated_index(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

Analysis analyze(const TriangleMesh& mesh) {
  Analysis a;
  MeshReport& r = a.report;
  const int n = int(mesh.vertices.size());
  const int m = int(mesh.triangles.size());
  r.vertices = n;
  r.faces = m;

  for (int v = 0; v < n; ++v) {
    if (!mesh.vertices[v].allFinite()) {
      if (r.non_finite_vertices++ == 0) a.first_non_finite = v;
    }
  }

  // Triangles that take part in the topology: in range and with three distinct corners.
  std::vector<char> usable(m, 1);
  for (int f = 0; f < m; ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int v : t) {
      if (v < 0 || v >= n) {
        usable[f] = 0;
        if (r.out_of_range_indices++ == 0) a.out_of_range_triangle = f, a.out_of_range_vertex = v;
      }
    }
    if (!usable[f]) continue;
    if (has_repeated_index(t)) {
      usable[f] = 0;
      ++r.degenerate_faces;
      if (a.repeated_index_triangle < 0) a.repeated_index_triangle = f;
    } else {
      const Vec3 &p0 = mesh.vertices[t[0]], &p1 = mesh.vertices[t[1]], &p2 = mesh.vertices[t[2]];
      if ((p1 - p0).cross(p2 - p0).squaredNorm() == 0) ++r.degenerate_faces;
    }
  }

  // Duplicate faces: same vertex set, whatever the order.
  {
    std::vector<std::pair<Triangle, int>> sorted;
    sorted.reserve(m);
    for (int f = 0; f < m; ++f) {
      if (!usable[f]) continue;
      Triangle t = mesh.triangles[f];
      std::sort(t.begin(), t.end());
      sorted.push_back({t, f});
    }
    std::sort(sorted.begin(), sorted.end());
    for (size_t i = 1; i < sorted.size(); ++i) {
      if (sorted[i].first != sorted[i - 1].first) continue;
      if (r.duplicate_faces++ == 0) a.duplicate_triangle = sorted[i].second, a.duplicate_of = sorted[i - 1].second;
    }
  }

  std::vector<char> referenced(n, 0);
  int usable_faces = 0;
  std::vector<Halfedge> halfedges;
  halfedges.reserve(3 * size_t(m));
  for (int f = 0; f < m; ++f) {
    if (!usable[f]) continue;
    ++usable_faces;
    const Triangle& t = mesh.triangles[f];
    for (int i = 0; i < 3; ++i) {
      const int u = t[i], w = t[(i + 1) % 3];
      referenced[u] = 1;
      halfedges.push_back({std::int64_t(std::min(u, w)) * n + std::max(u, w), f, u < w});
    }
  }
  for (int v = 0; v < n; ++v) {
    if (referenced[v]) ++r.referenced_vertices;
    else if (a.first_unreferenced < 0) a.first_unreferenced = v;
  }
  std::sort(halfedges.begin(), halfedges.end(),
            [](const Halfedge& x, const Halfedge& y) { return x.key < y.key || (x.key == y.key && x.face < y.face); });

  // Corners (face, local index) of a vertex are joined across manifold edges;
  // a vertex whose corners end up in more than one group is not one fan.
  const auto corner = [&](int f, int v) {
    const Triangle& t = mesh.triangles[f];
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  UnionFind connected(n), corners(3 * m);
  std::vector<std::pair<int, int>> boundary;  // boundary halfedges (from, to), as their triangle runs
  int edges = 0;
  for (size_t begin = 0, end; begin < halfedges.size(); begin = end) {
    for (end = begin + 1; end < halfedges.size() && halfedges[end].key == halfedges[begin].key; ++end) {}
    ++edges;
    const int lo = int(halfedges[begin].key / n), hi = int(halfedges[begin].key % n);
    const int count = int(end - begin);
    connected.unite(lo, hi);
    if (count == 1) {
      boundary.push_back(halfedges[begin].forward ? std::make_pair(lo, hi) : std::make_pair(hi, lo));
    } else if (count == 2) {
      const Halfedge &h0 = halfedges[begin], &h1 = halfedges[begin + 1];
      corners.unite(corner(h0.face, lo), corner(h1.face, lo));
      corners.unite(corner(h0.face, hi), corner(h1.face, hi));
      if (h0.forward == h1.forward && r.inconsistently_oriented_edges++ == 0)
        a.inconsistent_edge[0] = lo, a.inconsistent_edge[1] = hi;
    } else if (r.non_manifold_edges++ == 0) {
      a.non_manifold_edge[0] = lo, a.non_manifold_edge[1] = hi, a.non_manifold_edge_faces = count;
    }
  }

  // Components: triangles connected through shared vertices (a pinch vertex
  // joins two parts into one non-manifold component).
  std::vector<char> seen_root(n, 0);
  for (int v = 0; v < n; ++v) {
    if (!referenced[v]) continue;
    const int root = connected.find(v);
    if (!seen_root[root]) seen_root[root] = 1, ++r.components;
  }

  // Fans: distinct corner groups per vertex.
  std::vector<std::pair<int, int>> vertex_fans;  // (vertex, corner root)
  vertex_fans.reserve(3 * size_t(usable_faces));
  for (int f = 0; f < m; ++f) {
    if (!usable[f]) continue;
    for (int i = 0; i < 3; ++i) vertex_fans.push_back({mesh.triangles[f][i], corners.find(3 * f + i)});
  }
  std::sort(vertex_fans.begin(), vertex_fans.end());
  vertex_fans.erase(std::unique(vertex_fans.begin(), vertex_fans.end()), vertex_fans.end());
  for (size_t i = 1; i < vertex_fans.size(); ++i) {
    if (vertex_fans[i].first != vertex_fans[i - 1].first) continue;
    if (i >= 2 && vertex_fans[i - 2].first == vertex_fans[i].first) continue;  // count each vertex once
    if (r.non_manifold_vertices++ == 0) a.first_non_manifold_vertex = vertex_fans[i].first;
  }

  // Boundary loops: at each vertex the k-th boundary halfedge arriving is
  // continued by the k-th one leaving, so loops touching at a vertex stay apart.
  const int b = int(boundary.size());
  std::vector<int> arriving(b), leaving(b);
  std::iota(arriving.begin(), arriving.end(), 0);
  std::iota(leaving.begin(), leaving.end(), 0);
  std::sort(arriving.begin(), arriving.end(), [&](int x, int y) { return boundary[x].second < boundary[y].second; });
  std::sort(leaving.begin(), leaving.end(), [&](int x, int y) { return boundary[x].first < boundary[y].first; });
  UnionFind loops(b);
  for (int i = 0, j = 0; i < b && j < b;) {
    const int vi = boundary[arriving[i]].second, vj = boundary[leaving[j]].first;
    if (vi < vj) ++i;
    else if (vj < vi) ++j;
    else loops.unite(arriving[i++], leaving[j++]);
  }
  for (int h = 0; h < b; ++h) {
    if (loops.find(h) == h) ++r.boundary_loops;
  }

  r.euler_characteristic = r.referenced_vertices - edges + usable_faces;
  // chi = 2 - 2g - b holds for one orientable manifold component.
  const int twice_genus = 2 - r.euler_characteristic - r.boundary_loops;
  if (r.components == 1 && r.manifold() && twice_genus >= 0 && twice_genus % 2 == 0) r.genus = twice_genus / 2;
  return a;
}

std::string plural(int count, const std::string& noun) {
  if (count == 1) return "1 " + noun;
  const bool vertex = noun.size() >= 6 && noun.compare(noun.size() - 6, 6, "vertex") == 0;
  return std::to_string(count) + " " + (vertex ? noun.substr(0, noun.size() - 2) + "ices" : noun + "s");
}

std::string edge_name(const int (&e)[2]) { return std::to_string(e[0]) + "-" + std::to_string(e[1]); }

}  // namespace

MeshReport check_mesh(const TriangleMesh& mesh) { return analyze(mesh).report; }

std::string summarize(const MeshReport& r) {
  std::ostringstream s;
  s << plural(r.vertices, "vertex") << ", " << plural(r.faces, "triangle") << ", "
    << plural(r.components, "component") << ", ";
  if (r.closed()) s << "closed";
  else s << plural(r.boundary_loops, "boundary loop");
  s << ", " << (r.manifold() ? "manifold" : "non-manifold");
  if (r.genus >= 0) s << ", genus " << r.genus;
  s << ", Euler characteristic " << r.euler_characteristic;
  const std::pair<int, const char*> defects[] = {
      {r.vertices - r.referenced_vertices, "unreferenced vertex"},
      {r.non_manifold_edges, "non-manifold edge"},
      {r.non_manifold_vertices, "non-manifold vertex"},
      {r.degenerate_faces, "degenerate triangle"},
      {r.duplicate_faces, "duplicate triangle"},
      {r.inconsistently_oriented_edges, "inconsistently oriented edge"},
      {r.non_finite_vertices, "non-finite vertex"},
      {r.out_of_range_indices, "out-of-range index"},
  };
  for (const auto& [count, noun] : defects) {
    if (count > 0) s << ", " << plural(count, noun);
  }
  return s.str();
}

namespace {

// Throws InvalidInput / TopologyError naming the first defect that keeps the
// analysed mesh from being one manifold, consistently oriented surface of at
// least 4 triangles with finite coordinates (closed unless `allow_holes`);
// `needs` ("; <what> needs ") joins the defect to what it breaks.
void require_surface(const Analysis& a, const std::string& needs, bool allow_holes) {
  const MeshReport& r = a.report;

  if (r.vertices == 0) throw InvalidInput("mesh is empty (no vertices)");
  if (r.faces == 0) throw InvalidInput("mesh has no triangles");
  if (r.out_of_range_indices > 0)
    throw InvalidInput("triangle " + std::to_string(a.out_of_range_triangle) + " refers to vertex " +
                       std::to_string(a.out_of_range_vertex) + " but the mesh has " + plural(r.vertices, "vertex"));
  if (r.non_finite_vertices > 0)
    throw InvalidInput("vertex " + std::to_string(a.first_non_finite) + " has a non-finite coordinate" +
                       (r.non_finite_vertices > 1 ? " (" + plural(r.non_finite_vertices, "such vertex") + ")" : ""));
  if (r.faces < 4)
    throw TopologyError("mesh has only " + plural(r.faces, "triangle") + needs +
                        "a closed surface (at least 4 triangles)");
  if (a.repeated_index_triangle >= 0)
    throw TopologyError("triangle " + std::to_string(a.repeated_index_triangle) +
                        " uses the same vertex twice" + needs + "three distinct corners per triangle");
  if (r.components > 1) throw TopologyError("mesh has " + std::to_string(r.components) + " components" + needs +
                                            "one connected surface");
  if (r.duplicate_faces > 0)
    throw TopologyError("mesh has " + plural(r.duplicate_faces, "duplicate triangle") + " (e.g. triangle " +
                        std::to_string(a.duplicate_triangle) + " repeats triangle " +
                        std::to_string(a.duplicate_of) + ")" + needs + "each triangle once");
  if (r.non_manifold_edges > 0)
    throw TopologyError("mesh has " + plural(r.non_manifold_edges, "non-manifold edge") + " (e.g. edge " +
                        edge_name(a.non_manifold_edge) + " is shared by " +
                        std::to_string(a.non_manifold_edge_faces) + " triangles)" + needs + "a manifold surface");
  if (r.non_manifold_vertices > 0)
    throw TopologyError("mesh has " + plural(r.non_manifold_vertices, "non-manifold vertex") + " (e.g. vertex " +
                        std::to_string(a.first_non_manifold_vertex) + ")" + needs + "a manifold surface");
  if (r.boundary_loops > 0 && !allow_holes)
    throw TopologyError("mesh has " + plural(r.boundary_loops, "boundary loop") + needs +
                        "a closed surface (fill the holes first)");
  if (r.inconsistently_oriented_edges > 0)
    throw TopologyError("mesh has " + plural(r.inconsistently_oriented_edges, "inconsistently oriented edge") +
                        " (e.g. edge " + edge_name(a.inconsistent_edge) + ")" + needs +
                        "consistently oriented triangles");
}

}  // namespace

void require_sphere_topology(const TriangleMesh& mesh, bool allow_holes) {
  const Analysis a = analyze(mesh);
  const MeshReport& r = a.report;
  const std::string needs = "; spherical parameterization needs ";
  require_surface(a, needs, allow_holes);
  if (r.genus != 0)
    throw TopologyError("mesh has genus " + std::to_string(r.genus) + " (" +
                        (r.boundary_loops > 0 ? plural(r.boundary_loops, "boundary loop") : "closed") +
                        ", 1 component)" + needs + "genus 0");
  // Last: stray vertices are the easiest defect to fix and hide nothing else.
  if (r.referenced_vertices < r.vertices)
    throw InvalidInput("mesh has " + plural(r.vertices - r.referenced_vertices, "unreferenced vertex") +
                       " (e.g. vertex " + std::to_string(a.first_unreferenced) +
                       "); every vertex must belong to a triangle to get a position on the sphere");
}

MeshReport require_pair_map_topology(const TriangleMesh& mesh) {
  const Analysis a = analyze(mesh);
  require_surface(a, "; an inter-surface map needs ", /*allow_holes=*/true);
  return a.report;
}

double signed_volume(const TriangleMesh& mesh) {
  double volume = 0;
  for (const Triangle& t : mesh.triangles)
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  return volume / 6;
}

double surface_area(const TriangleMesh& mesh) {
  double area = 0;
  for (const Triangle& t : mesh.triangles)
    area += 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
  return area;
}

}  // namespace cmaps
