#include "consistent_maps/pair_remesh.h"

#include <cstdlib>
#include <string>
#include <utility>

#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/progressive_mesh.h"
#include "common/side_by_side.h"
#include "paths/mesh_holes.h"
#include "remesh/unfolding_flips.h"

namespace cmaps {
namespace {

// Per vertex: whether a triangle uses it (indices already checked).
std::vector<char> used_vertices(const TriangleMesh& mesh) {
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const Triangle& t : mesh.triangles)
    for (int v : t) used[v] = 1;
  return used;
}

// Each used carrier vertex's image on the partner and the partner's normal
// there (its vertex normals interpolated); unused vertices get zeros.
void images(const TriangleMesh& carrier, const TriangleMesh& partner, const std::vector<SurfacePoint>& points,
            std::vector<Vec3>& positions, std::vector<Vec3>& normals) {
  const std::vector<char> used = used_vertices(carrier);
  const std::vector<Vec3> vertex = vertex_normals(partner);
  positions.assign(points.size(), Vec3::Zero());
  normals.assign(points.size(), Vec3::Zero());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!used[i]) continue;
    const SurfacePoint& p = points[i];
    if (p.triangle < 0 || p.triangle >= int(partner.triangles.size()))
      throw InvalidInput("carrier vertex " + std::to_string(i) + " maps onto triangle " + std::to_string(p.triangle) +
                         " but the partner has " + std::to_string(partner.triangles.size()) + " triangles");
    for (int k = 0; k < 3; ++k) {
      const int corner = partner.triangles[p.triangle][k];
      positions[i] += p.barycentric[k] * partner.vertices[corner];
      normals[i] += p.barycentric[k] * vertex[corner];
    }
  }
}

// Each hole's centre at its rim's centroid in `x`, whose input vertices are set.
void place_centres(const ClosedMesh& closed, std::vector<Vec3>& x) {
  for (std::size_t h = 0; h < closed.loops.size(); ++h) {
    Vec3 sum = Vec3::Zero();
    for (int v : closed.loops[h]) sum += x[v];
    x[closed.centre(int(h))] = sum / double(closed.loops[h].size());
  }
}

// The remesh with `carrier` simplified (positions: the carrier's first).
PairRemesh remesh_carried(const TriangleMesh& carrier, const TriangleMesh& partner,
                          const std::vector<SurfacePoint>& carrier_on_partner, const std::vector<int>& features,
                          int target_vertices) {
  const ClosedMesh closed = close_holes(carrier, true);
  const int n = int(closed.mesh.vertices.size());

  std::vector<Vec3> on_partner, partner_normals;
  images(carrier, partner, carrier_on_partner, on_partner, partner_normals);
  on_partner.resize(n);
  place_centres(closed, on_partner);
  // Meshes may face opposite ways (one's triangles listed inwards): the
  // partner's normals are turned when most images of carrier triangles face against them.
  int against = 0;
  for (const Triangle& t : carrier.triangles) against += folds({on_partner, partner_normals}, t) ? 1 : -1;
  if (against > 0)
    for (Vec3& normal : partner_normals) normal = -normal;
  const std::vector<Vec3> fan_normals = vertex_normals({on_partner, closed.mesh.triangles});
  partner_normals.insert(partner_normals.end(), fan_normals.begin() + closed.input_vertices, fan_normals.end());

  SimplificationOptions options;
  options.extra_geometries = {on_partner};
  options.reference_normals = {vertex_normals(closed.mesh), partner_normals};
  options.locked.assign(n, 0);
  for (int f : features) options.locked[f] = 1;
  for (int h = 0; h < int(closed.loops.size()); ++h) {
    options.locked[closed.centre(h)] = 1;
    const auto& loop = closed.loops[h];
    for (std::size_t j = 0; j < loop.size(); ++j) options.path_edges.push_back({loop[j], loop[(j + 1) % loop.size()]});
  }
  options.target_vertices = target_vertices + int(closed.loops.size());
  options.finish_without_geometric_tests = false;
  const ProgressiveMesh pm = build_progressive_mesh(closed.mesh, options);

  PairRemesh remesh;
  std::vector<int> index(n, -1);
  for (int v = 0; v < closed.input_vertices; ++v)
    if (pm.base_vertex_active[v]) {
      index[v] = int(remesh.carrier_vertex.size());
      remesh.carrier_vertex.push_back(v);
      remesh.a_positions.push_back(carrier.vertices[v]);
      remesh.b_positions.push_back(on_partner[v]);
    }
  // What the collapses could not unfold, flips may (the holes' fans stay).
  std::vector<Triangle> kept;
  std::vector<char> surface;
  for (int f = 0; f < int(pm.base_triangles.size()); ++f)
    if (pm.base_face_active[f]) kept.push_back(pm.base_triangles[f]), surface.push_back(f < closed.input_triangles);
  const std::vector<FoldGeometry> geometries{{closed.mesh.vertices, options.reference_normals[0]},
                                             {on_partner, options.reference_normals[1]}};
  unfold_by_flips(kept, surface, geometries);
  for (std::size_t f = 0; f < kept.size(); ++f) {
    if (!surface[f]) continue;
    const Triangle& t = kept[f];
    remesh.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    remesh.folded_triangles += folds(geometries[0], t) || folds(geometries[1], t);
  }
  for (int f : features) remesh.feature_vertices.push_back(index[f]);
  return remesh;
}

// Which mesh's vertex each pair names (A's or B's), checked: in range and used by a triangle.
std::vector<int> feature_vertices(const std::vector<FeaturePair>& features, const TriangleMesh& mesh, bool of_b) {
  const std::vector<char> used = used_vertices(mesh);
  const std::string name = of_b ? "B" : "A";
  std::vector<int> vertices;
  for (const FeaturePair& p : features) {
    const int v = of_b ? p.b : p.a;
    if (v < 0 || v >= int(mesh.vertices.size()))
      throw InvalidInput("feature vertex " + std::to_string(v) + " out of range (" + name + " has " +
                         std::to_string(mesh.vertices.size()) + " vertices)");
    if (!used[v]) throw InvalidInput("feature vertex " + std::to_string(v) + " of " + name + " is in no triangle");
    vertices.push_back(v);
  }
  return vertices;
}

void require_images(const std::vector<SurfacePoint>& images, const TriangleMesh& source, const char* name) {
  if (images.size() != source.vertices.size())
    throw InvalidInput(std::to_string(images.size()) + " images for the " + std::to_string(source.vertices.size()) +
                       " vertices of " + name);
}

}  // namespace

PairRemesh remesh_pair(const TriangleMesh& a, const TriangleMesh& b, const std::vector<SurfacePoint>& a_on_b,
                       const std::vector<SurfacePoint>& b_on_a, const std::vector<FeaturePair>& features,
                       int target_vertices) {
  require_images(a_on_b, a, "A");
  require_images(b_on_a, b, "B");
  if (target_vertices < 4)
    throw InvalidInput("a remesh needs at least 4 vertices, not " + std::to_string(target_vertices));
  require_pair_map_topology(a);
  require_pair_map_topology(b);
  const std::vector<int> features_a = feature_vertices(features, a, false);
  const std::vector<int> features_b = feature_vertices(features, b, true);
  PairRemesh by_a, by_b;
  for (const std::exception_ptr& thrown : run_side_by_side(
           {}, 0.5, [&](const ProgressCallback&) { by_a = remesh_carried(a, b, a_on_b, features_a, target_vertices); },
           [&](const ProgressCallback&) { by_b = remesh_carried(b, a, b_on_a, features_b, target_vertices); }))
    if (thrown) std::rethrow_exception(thrown);
  std::swap(by_b.a_positions, by_b.b_positions);
  by_b.b_carries = true;
  const auto rank = [&](const PairRemesh& r) {
    return std::pair{r.folded_triangles, std::abs(int(r.carrier_vertex.size()) - target_vertices)};
  };
  return rank(by_b) < rank(by_a) ? by_b : by_a;
}

}  // namespace cmaps
