#include "consistent_maps/progressive_mesh.h"

#include <algorithm>
#include <queue>

#include "common/ring.h"
#include "consistent_maps/errors.h"
#include "progressive_mesh/quadric.h"

namespace cmaps {
namespace {

// One collapse candidate per vertex lives in the heap; `stamp` invalidates
// candidates computed before the vertex's neighbourhood last changed.
struct Candidate {
  double cost;
  int from, to;
  unsigned stamp;
  bool operator<(const Candidate& o) const { return cost > o.cost; }  // min-heap
};

class Simplifier {
 public:
  Simplifier(const TriangleMesh& mesh, const SimplificationOptions& options)
      : options_(options), tris_(mesh.triangles) {
    const int n = static_cast<int>(mesh.vertices.size());
    geometries_.push_back(&mesh.vertices);
    for (const auto& g : options.extra_geometries) {
      if (static_cast<int>(g.size()) != n)
        throw InvalidInput("extra geometry has " + std::to_string(g.size()) + " vertices, expected " +
                           std::to_string(n));
      geometries_.push_back(&g);
    }
    if (options.reference_normals.size() > geometries_.size())
      throw InvalidInput("reference normals for " + std::to_string(options.reference_normals.size()) +
                         " geometries, expected at most " + std::to_string(geometries_.size()));
    for (const auto& normals : options.reference_normals)
      if (!normals.empty() && static_cast<int>(normals.size()) != n)
        throw InvalidInput("reference normals for " + std::to_string(normals.size()) + " vertices, expected " +
                           std::to_string(n));
    face_alive_.assign(tris_.size(), 1);
    vertex_alive_.assign(n, 0);
    vertex_faces_.resize(n);
    for (int f = 0; f < static_cast<int>(tris_.size()); ++f)
      for (int v : tris_[f]) {
        vertex_faces_[v].push_back(f);
        vertex_alive_[v] = 1;
      }
    alive_ = static_cast<int>(std::count(vertex_alive_.begin(), vertex_alive_.end(), 1));
    locked_ = options.locked.empty() ? std::vector<char>(n, 0) : options.locked;
    if (static_cast<int>(locked_.size()) != n) throw InvalidInput("locked flags do not match the vertex count");
    init_paths(n);
    chains_of_.assign(n, {});
    for (int c = 0; c < static_cast<int>(options.chains.size()); ++c)
      for (int v : options.chains[c]) {
        if (v < 0 || v >= n) throw InvalidInput("chain refers to a missing vertex");
        chains_of_[v].push_back(c);
      }
    init_quadrics(n);
    stamp_.assign(n, 0);
  }

  ProgressiveMesh run(const ProgressCallback& progress) {
    ProgressSlice report(progress, "simplify", 0.0, 1.0);
    const int start = alive_;
    std::vector<VertexSplit> collapses;
    for (strict_ = true;; strict_ = false) {
      heap_ = {};
      for (int v = 0; v < static_cast<int>(vertex_alive_.size()); ++v)
        if (vertex_alive_[v]) push_candidate(v);
      while (alive_ > options_.target_vertices && !heap_.empty()) {
        const Candidate c = heap_.top();
        heap_.pop();
        if (!vertex_alive_[c.from] || c.stamp != stamp_[c.from]) continue;
        collapses.push_back(collapse(c.from, c.to));
        if (collapses.size() % 2048 == 0)
          report.report(double(start - alive_) / std::max(1, start - options_.target_vertices));
      }
      // The geometric tests can block every remaining collapse; the topology
      // alone never blocks one before a tetrahedron, so finish without them.
      if (!strict_ || alive_ <= options_.target_vertices || !options_.finish_without_geometric_tests) break;
    }
    ProgressiveMesh pm;
    pm.vertex_count = static_cast<int>(vertex_alive_.size());
    pm.base_triangles = std::move(tris_);
    pm.base_face_active = std::move(face_alive_);
    pm.base_vertex_active = std::move(vertex_alive_);
    pm.splits.assign(collapses.rbegin(), collapses.rend());
    pm.changed_faces = std::move(changed_faces_);
    return pm;
  }

 private:
  void init_paths(int n) {
    path_neighbours_.assign(n, {});
    for (const auto& e : options_.path_edges) {
      for (int v : e)
        if (v < 0 || v >= n) throw InvalidInput("path edge refers to a missing vertex");
      path_neighbours_[e[0]].push_back(e[1]);
      path_neighbours_[e[1]].push_back(e[0]);
    }
    // Ends and junctions of paths must stay: lock them.
    for (int v = 0; v < n; ++v)
      if (!path_neighbours_[v].empty() && path_neighbours_[v].size() != 2) locked_[v] = 1;
  }

  void init_quadrics(int n) {
    const size_t g_count = geometries_.size();
    quadrics_.assign(n * g_count, Quadric());
    for (size_t g = 0; g < g_count; ++g) {
      const auto& x = *geometries_[g];
      for (const Triangle& t : tris_) {
        const Quadric q = Quadric::of_triangle(x[t[0]], x[t[1]], x[t[2]]);
        for (int v : t) quadrics_[v * g_count + g] += q;
      }
    }
  }

  std::vector<int> neighbours(int v) const {
    std::vector<int> result;
    for (int f : vertex_faces_[v])
      for (int w : tris_[f])
        if (w != v) result.push_back(w);
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
  }

  double cost(int u, int v) const {
    const size_t g_count = geometries_.size();
    double c = 0;
    for (size_t g = 0; g < g_count; ++g) {
      Quadric q = quadrics_[u * g_count + g];
      q += quadrics_[v * g_count + g];
      c += q.error((*geometries_[g])[v]);
    }
    return c;
  }

  bool path_allows(int u, int v) const {
    const auto& p = path_neighbours_[u];
    return p.empty() || std::find(p.begin(), p.end(), v) != p.end();
  }

  // No new edge between two vertices of one chain, unless u lies on it.
  bool chords_ok(int u, int v, const std::vector<int>& nu) const {
    if (chains_of_[v].empty()) return true;
    const std::vector<int> nv = neighbours(v);
    for (int w : nu) {
      if (w == v || chains_of_[w].empty() || std::binary_search(nv.begin(), nv.end(), w)) continue;
      for (int c : chains_of_[v])
        if (std::find(chains_of_[w].begin(), chains_of_[w].end(), c) != chains_of_[w].end() &&
            std::find(chains_of_[u].begin(), chains_of_[u].end(), c) == chains_of_[u].end())
          return false;
    }
    return true;
  }

  // Link condition: the only common neighbours of u and v are the apexes of
  // the two triangles on edge uv, which keeps the mesh a manifold.
  bool link_ok(int v, const std::vector<int>& nu) const {
    const std::vector<int> nv = neighbours(v);
    int common = 0;
    for (int w : nu)
      if (std::binary_search(nv.begin(), nv.end(), w)) ++common;
    return common == 2;
  }

  // Moving u onto v must not flip (or, for a positive-area triangle, fold)
  // any triangle that survives, in any geometry. Against reference normals,
  // a triangle facing along them must keep doing so; one facing against them
  // may turn over (that unfolds it).
  bool geometry_ok(int u, int v) const {
    for (size_t g = 0; g < geometries_.size(); ++g) {
      const auto* x = geometries_[g];
      const bool referenced = g < options_.reference_normals.size() && !options_.reference_normals[g].empty();
      for (int f : vertex_faces_[u]) {
        const Triangle& t = tris_[f];
        if (t[0] == v || t[1] == v || t[2] == v) continue;
        const int k = t[0] == u ? 0 : t[1] == u ? 1 : 2;
        const Vec3& a = (*x)[t[(k + 1) % 3]];
        const Vec3& b = (*x)[t[(k + 2) % 3]];
        const Vec3 before = (a - (*x)[u]).cross(b - (*x)[u]);
        const Vec3 after = (a - (*x)[v]).cross(b - (*x)[v]);
        if (referenced) {
          const auto& n = options_.reference_normals[g];
          const Vec3 shared = n[t[(k + 1) % 3]] + n[t[(k + 2) % 3]];
          const bool folded = before.dot(shared + n[u]) <= 0;
          if (!folded && (before.dot(after) <= 0 || after.dot(shared + n[v]) <= 0)) return false;
        } else if (before.squaredNorm() > 0 && before.dot(after) <= 0) {
          return false;
        }
      }
    }
    return true;
  }

  // How many triangles of u's star facing against the reference normals
  // moving u onto v turns (or collapses) away, less those it turns against.
  int folds_removed(int u, int v) const {
    int removed = 0;
    for (size_t g = 0; g < geometries_.size() && g < options_.reference_normals.size(); ++g) {
      const auto& n = options_.reference_normals[g];
      if (n.empty()) continue;
      const auto& x = *geometries_[g];
      for (int f : vertex_faces_[u]) {
        const Triangle& t = tris_[f];
        const Vec3 r = n[t[0]] + n[t[1]] + n[t[2]];
        removed += (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).dot(r) <= 0;
        if (t[0] == v || t[1] == v || t[2] == v) continue;
        const int k = t[0] == u ? 0 : t[1] == u ? 1 : 2;
        const Vec3& a = x[t[(k + 1) % 3]];
        const Vec3& b = x[t[(k + 2) % 3]];
        removed -= (a - x[v]).cross(b - x[v]).dot(r - n[u] + n[v]) <= 0;
      }
    }
    return removed;
  }

  void push_candidate(int u) {
    ++stamp_[u];
    if (locked_[u] || !vertex_alive_[u]) return;
    const std::vector<int> nu = neighbours(u);
    std::vector<std::pair<double, int>> options;
    for (int v : nu)
      if (path_allows(u, v)) {
        // Unfolding collapses go first, whatever their quadric error.
        const int unfolded = options_.reference_normals.empty() ? 0 : folds_removed(u, v);
        options.emplace_back(unfolded > 0 ? -unfolded : cost(u, v), v);
      }
    std::sort(options.begin(), options.end());
    for (const auto& [c, v] : options) {
      if (!link_ok(v, nu) || !chords_ok(u, v, nu) || (strict_ && !geometry_ok(u, v))) continue;
      heap_.push({c, u, v, stamp_[u]});
      return;
    }
  }

  VertexSplit collapse(int u, int v) {
    VertexSplit s;
    s.removed = u;
    s.kept = v;
    s.changed_begin = static_cast<int>(changed_faces_.size());
    for (int f : vertex_faces_[u]) {
      Triangle& t = tris_[f];
      const int k = t[0] == u ? 0 : t[1] == u ? 1 : 2;
      const int a = t[(k + 1) % 3], b = t[(k + 2) % 3];
      if (a == v || b == v) {
        // Triangle (u, v, right) or (u, left, v): it disappears.
        if (a == v) {
          if (s.face_right >= 0) throw TopologyError("mesh is not closed and manifold");
          s.face_right = f;
          s.right = b;
        } else {
          if (s.face_left >= 0) throw TopologyError("mesh is not closed and manifold");
          s.face_left = f;
          s.left = a;
        }
        face_alive_[f] = 0;
        for (int w : t)
          if (w != u) erase_face(w, f);
      } else {
        t[k] = v;
        vertex_faces_[v].push_back(f);
        changed_faces_.push_back(f);
      }
    }
    if (s.face_left < 0 || s.face_right < 0) throw TopologyError("mesh is not closed and manifold");
    s.changed_end = static_cast<int>(changed_faces_.size());
    vertex_faces_[u].clear();
    vertex_alive_[u] = 0;
    --alive_;
    const size_t g_count = geometries_.size();
    for (size_t g = 0; g < g_count; ++g) quadrics_[v * g_count + g] += quadrics_[u * g_count + g];
    update_paths(u, v);
    push_candidate(v);
    for (int w : neighbours(v)) push_candidate(w);
    return s;
  }

  void update_paths(int u, int v) {
    auto& pu = path_neighbours_[u];
    if (pu.empty()) return;
    const int other = pu[0] == v ? pu[1] : pu[0];
    auto& pv = path_neighbours_[v];
    std::replace(pv.begin(), pv.end(), u, other);
    auto& po = path_neighbours_[other];
    std::replace(po.begin(), po.end(), u, v);
    pu.clear();
  }

  void erase_face(int v, int f) {
    auto& list = vertex_faces_[v];
    auto it = std::find(list.begin(), list.end(), f);
    *it = list.back();
    list.pop_back();
  }

  const SimplificationOptions& options_;
  std::vector<const std::vector<Vec3>*> geometries_;
  std::vector<Triangle> tris_;
  std::vector<char> face_alive_, vertex_alive_, locked_;
  std::vector<std::vector<int>> vertex_faces_, path_neighbours_, chains_of_;
  std::vector<Quadric> quadrics_;  // vertex-major, one per geometry
  std::vector<unsigned> stamp_;
  std::vector<int> changed_faces_;
  std::priority_queue<Candidate> heap_;
  int alive_ = 0;
  bool strict_ = true;
};

}  // namespace

ProgressiveMesh build_progressive_mesh(const TriangleMesh& mesh, const SimplificationOptions& options,
                                       const ProgressCallback& progress) {
  return Simplifier(mesh, options).run(progress);
}

MeshRefinement::MeshRefinement(const ProgressiveMesh& pm)
    : pm_(pm),
      triangles_(pm.base_triangles),
      face_active_(pm.base_face_active),
      vertex_active_(pm.base_vertex_active),
      vertex_faces_(pm.vertex_count) {
  active_vertices_ = static_cast<int>(std::count(vertex_active_.begin(), vertex_active_.end(), 1));
  for (int f = 0; f < static_cast<int>(triangles_.size()); ++f)
    if (face_active_[f])
      for (int v : triangles_[f]) vertex_faces_[v].push_back(f);
}

const VertexSplit& MeshRefinement::apply_next_split() {
  const VertexSplit& s = pm_.splits[next_++];
  auto& kept_faces = vertex_faces_[s.kept];
  for (int i = s.changed_begin; i < s.changed_end; ++i) {
    const int f = pm_.changed_faces[i];
    std::replace(triangles_[f].begin(), triangles_[f].end(), s.kept, s.removed);
    auto it = std::find(kept_faces.begin(), kept_faces.end(), f);
    *it = kept_faces.back();
    kept_faces.pop_back();
    vertex_faces_[s.removed].push_back(f);
  }
  for (int f : {s.face_left, s.face_right}) {
    face_active_[f] = 1;
    for (int v : triangles_[f]) vertex_faces_[v].push_back(f);
  }
  vertex_active_[s.removed] = 1;
  ++active_vertices_;
  return s;
}

std::vector<int> MeshRefinement::ring(int v) const {
  std::vector<Triangle> star;
  for (int f : vertex_faces_[v]) star.push_back(triangles_[f]);
  return ring_around(v, star);
}

std::vector<Triangle> MeshRefinement::active_triangles() const {
  std::vector<Triangle> result;
  for (size_t f = 0; f < triangles_.size(); ++f)
    if (face_active_[f]) result.push_back(triangles_[f]);
  return result;
}

}  // namespace cmaps
