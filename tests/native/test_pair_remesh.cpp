// Consistent remeshes of a pair: one connectivity on both surfaces, each
// vertex on its own surface, genus and holes kept, features at identical
// indices, folds of the map's vertex sampling collapsed away; bad input refused.
#include <gtest/gtest.h>

#include <map>
#include <numeric>
#include <random>
#include <set>

#include "consistent_maps/errors.h"
#include "consistent_maps/geometry_image.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "consistent_maps/pair_remesh.h"
#include "consistent_maps/progressive_mesh.h"
#include "test_support.h"

namespace cmaps {
namespace {

// The partner: `mesh` turned, scaled, moved and re-indexed (vertex v becomes
// order[v]); `image` takes each vertex to its copy and `back` each copy to
// its vertex (the corner of a triangle holding it, weight 1).
struct Copy {
  TriangleMesh partner;
  std::vector<int> order;
  std::vector<SurfacePoint> image, back;
  Vec3 place(const Vec3& x) const { return 1.7 * Vec3(x.y(), -x.x(), x.z()) + Vec3(3, 0, -1); }
  FeaturePair pair(int v) const { return {v, order[v]}; }
};

Copy moved_copy(const TriangleMesh& mesh, bool inwards = false) {
  Copy copy;
  std::vector<int>& order = copy.order;
  order.resize(mesh.vertices.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  copy.partner.vertices.resize(order.size());
  for (std::size_t v = 0; v < order.size(); ++v) copy.partner.vertices[order[v]] = copy.place(mesh.vertices[v]);
  copy.image.resize(order.size());
  copy.back.resize(order.size());
  for (const Triangle& t : mesh.triangles) {
    const int f = int(copy.partner.triangles.size());
    copy.partner.triangles.push_back({order[t[0]], order[t[1]], order[t[2]]});
    if (inwards) std::swap(copy.partner.triangles.back()[1], copy.partner.triangles.back()[2]);
    for (int k = 0; k < 3; ++k) {
      std::array<double, 3> corner{0, 0, 0};
      corner[inwards && k ? 3 - k : k] = 1;
      copy.image[t[k]] = {f, corner};
      copy.back[order[t[k]]] = {f, corner};
    }
  }
  return copy;
}

int folded_on(const TriangleMesh& surface, const std::vector<Vec3>& x, const std::vector<Triangle>& triangles,
              const std::vector<int>& surface_vertex) {
  const std::vector<Vec3> normals = vertex_normals(surface);
  int folded = 0;
  for (const Triangle& t : triangles) {
    Vec3 reference = Vec3::Zero();
    for (int v : t) reference += normals[surface_vertex[v]];
    folded += (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).dot(reference) <= 0;
  }
  return folded;
}

// Triangles facing against `surface` of a mesh whose every vertex sits exactly on one of its vertices.
int folded_on(const TriangleMesh& surface, const std::vector<Vec3>& x, const std::vector<Triangle>& triangles) {
  std::map<std::array<double, 3>, int> vertex_at;
  for (std::size_t v = 0; v < surface.vertices.size(); ++v)
    vertex_at[{surface.vertices[v].x(), surface.vertices[v].y(), surface.vertices[v].z()}] = int(v);
  std::vector<int> on;
  for (const Vec3& p : x) on.push_back(vertex_at.at({p.x(), p.y(), p.z()}));
  return folded_on(surface, x, triangles, on);
}

TEST(PairRemesh, BothSurfacesShareOneConnectivityAndKeepTheirGenus) {
  const TriangleMesh torus = read_mesh(test::shared_mesh("higher-genus/torus.obj"));
  const Copy copy = moved_copy(torus);
  const std::vector<int> features{0, 700, 1500};
  const PairRemesh remesh = remesh_pair(torus, copy.partner, copy.image, copy.back,
                                        {copy.pair(0), copy.pair(700), copy.pair(1500)}, 500);
  ASSERT_EQ(remesh.carrier_vertex.size(), 500u);
  EXPECT_EQ(std::set<int>(remesh.carrier_vertex.begin(), remesh.carrier_vertex.end()).size(), 500u);
  const auto& carrier = remesh.b_carries ? copy.partner : torus;
  for (std::size_t v = 0; v < 500; ++v) {
    const Vec3& own = remesh.b_carries ? remesh.b_positions[v] : remesh.a_positions[v];
    EXPECT_EQ(own, carrier.vertices[remesh.carrier_vertex[v]]);
    EXPECT_LT((remesh.b_positions[v] - copy.place(remesh.a_positions[v])).norm(), 1e-12);
  }
  for (std::size_t k = 0; k < features.size(); ++k)
    EXPECT_EQ(remesh.a_positions[remesh.feature_vertices[k]], torus.vertices[features[k]]);
  const MeshReport report = check_mesh({remesh.a_positions, remesh.triangles});
  EXPECT_EQ(report.euler_characteristic, 0);  // still a torus
  EXPECT_TRUE(report.closed());
  EXPECT_EQ(report.inconsistently_oriented_edges, 0);
  EXPECT_EQ(remesh.folded_triangles, 0);
}

TEST(PairRemesh, AMeshListedInwardsIsJudgedByItsOwnSide) {
  const TriangleMesh torus = read_mesh(test::shared_mesh("higher-genus/torus.obj"));
  const Copy copy = moved_copy(torus, true);
  EXPECT_GT(folded_on(copy.partner, surface_positions(copy.partner, copy.image), torus.triangles),
            int(torus.triangles.size()) - 10);  // every image faces against the partner's own normals
  const PairRemesh remesh = remesh_pair(torus, copy.partner, copy.image, copy.back, {}, 500);
  EXPECT_EQ(remesh.carrier_vertex.size(), 500u);
  EXPECT_EQ(remesh.folded_triangles, 0);
}

TEST(PairRemesh, HolesStayHolesTheirRimsShortenedAlongThemselves) {
  const TriangleMesh bunny = read_mesh(test::shared_mesh("boundary/bunny_holes.obj"));
  const MeshReport input = check_mesh(bunny);
  ASSERT_GE(input.boundary_loops, 2);
  const Copy copy = moved_copy(bunny);
  const PairRemesh remesh = remesh_pair(bunny, copy.partner, copy.image, copy.back, {}, 400);
  EXPECT_EQ(remesh.carrier_vertex.size(), 400u);
  ASSERT_FALSE(remesh.b_carries);  // a tie: A's
  const MeshReport report = check_mesh({remesh.a_positions, remesh.triangles});
  EXPECT_EQ(report.boundary_loops, input.boundary_loops);
  EXPECT_EQ(report.euler_characteristic, input.euler_characteristic);
  EXPECT_TRUE(report.manifold());
  // Each rim edge of the remesh joins two vertices of one input rim.
  std::map<int, int> loop_of;
  std::map<std::pair<int, int>, int> half_edges;
  for (const Triangle& t : bunny.triangles)
    for (int k = 0; k < 3; ++k) ++half_edges[{t[k], t[(k + 1) % 3]}];
  std::map<int, int> next;
  for (const auto& [edge, count] : half_edges)
    if (!half_edges.count({edge.second, edge.first})) next[edge.first] = edge.second;
  int loops = 0;
  for (const auto& [start, unused] : next) {
    if (loop_of.count(start)) continue;
    for (int v = start; !loop_of.count(v); v = next.at(v)) loop_of[v] = loops;
    ++loops;
  }
  std::map<std::pair<int, int>, int> remesh_edges;
  for (const Triangle& t : remesh.triangles)
    for (int k = 0; k < 3; ++k) ++remesh_edges[{t[k], t[(k + 1) % 3]}];
  int rim_edges = 0;
  for (const auto& [edge, count] : remesh_edges) {
    if (remesh_edges.count({edge.second, edge.first})) continue;
    ++rim_edges;
    const int a = remesh.carrier_vertex[edge.first], b = remesh.carrier_vertex[edge.second];
    ASSERT_TRUE(loop_of.count(a) && loop_of.count(b));
    EXPECT_EQ(loop_of[a], loop_of[b]);
  }
  EXPECT_GE(rim_edges, 3 * input.boundary_loops);
  EXPECT_EQ(remesh.folded_triangles, 0);
}

TEST(PairRemesh, FoldsOfTheMapsSamplingAreCollapsedAway) {
  const TriangleMesh torus = read_mesh(test::shared_mesh("higher-genus/torus.obj"));
  Copy copy = moved_copy(torus);
  // Swap the images of both ends of every 40th edge, both ways: the chord triangles around them fold.
  for (std::size_t f = 0; f < torus.triangles.size(); f += 40) {
    std::swap(copy.image[torus.triangles[f][0]], copy.image[torus.triangles[f][1]]);
    const Triangle& t = copy.partner.triangles[(f + 20) % copy.partner.triangles.size()];
    std::swap(copy.back[t[0]], copy.back[t[1]]);
  }
  const std::vector<Vec3> on_partner = surface_positions(copy.partner, copy.image);
  ASSERT_GE(folded_on(copy.partner, on_partner, torus.triangles), 100);
  ASSERT_GE(folded_on(torus, surface_positions(torus, copy.back), copy.partner.triangles), 100);

  // Simplifying both geometries by their quadrics alone keeps many of them.
  SimplificationOptions plain;
  plain.extra_geometries = {on_partner};
  plain.target_vertices = 1000;
  const ProgressiveMesh pm = build_progressive_mesh(torus, plain);
  std::vector<Triangle> kept;
  for (std::size_t f = 0; f < pm.base_triangles.size(); ++f)
    if (pm.base_face_active[f]) kept.push_back(pm.base_triangles[f]);
  std::vector<int> alive;
  std::vector<int> index(torus.vertices.size(), -1);
  for (int v = 0; v < int(torus.vertices.size()); ++v)
    if (pm.base_vertex_active[v]) index[v] = int(alive.size()), alive.push_back(v);
  std::vector<Vec3> kept_on_partner;
  for (int v : alive) kept_on_partner.push_back(on_partner[v]);
  for (Triangle& t : kept) t = {index[t[0]], index[t[1]], index[t[2]]};
  EXPECT_GE(folded_on(copy.partner, kept_on_partner, kept), 20);

  const PairRemesh remesh = remesh_pair(torus, copy.partner, copy.image, copy.back, {}, 1000);
  EXPECT_EQ(remesh.carrier_vertex.size(), 1000u);
  EXPECT_EQ(folded_on(torus, remesh.a_positions, remesh.triangles), 0);
  EXPECT_EQ(folded_on(copy.partner, remesh.b_positions, remesh.triangles), 0);
  EXPECT_EQ(remesh.folded_triangles, 0);
}

TEST(PairRemesh, BadInputIsRefusedWithItsReason) {
  const TriangleMesh torus = read_mesh(test::shared_mesh("higher-genus/torus.obj"));
  const Copy copy = moved_copy(torus);
  std::vector<SurfacePoint> short_image(copy.image.begin(), copy.image.end() - 1);
  EXPECT_THROW(remesh_pair(torus, copy.partner, short_image, copy.back, {}, 100), InvalidInput);
  EXPECT_THROW(remesh_pair(torus, copy.partner, copy.image, short_image, {}, 100), InvalidInput);
  EXPECT_THROW(remesh_pair(torus, copy.partner, copy.image, copy.back, {}, 3), InvalidInput);
  EXPECT_THROW(remesh_pair(torus, copy.partner, copy.image, copy.back, {{int(torus.vertices.size()), 0}}, 100),
               InvalidInput);
  EXPECT_THROW(remesh_pair(torus, copy.partner, copy.image, copy.back, {{0, -1}}, 100), InvalidInput);
  TriangleMesh loose = torus;
  loose.vertices.push_back({9, 9, 9});  // used by no triangle: dropped, but no feature
  std::vector<SurfacePoint> loose_image = copy.image;
  loose_image.push_back(copy.image[0]);
  EXPECT_EQ(remesh_pair(loose, copy.partner, loose_image, copy.back, {}, 100).carrier_vertex.size(), 100u);
  EXPECT_THROW(remesh_pair(loose, copy.partner, loose_image, copy.back, {{int(torus.vertices.size()), 0}}, 100),
               InvalidInput);
  std::vector<SurfacePoint> off = copy.image;
  off[5].triangle = int(copy.partner.triangles.size());
  try {
    remesh_pair(torus, copy.partner, off, copy.back, {}, 100);
    FAIL() << "an image off the partner's triangles was taken";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("carrier vertex 5 maps onto triangle"), std::string::npos) << e.what();
  }
  const TriangleMesh broken = read_mesh(test::shared_mesh("invalid/dino_nonmanifold_edges.off"));
  const std::vector<SurfacePoint> anywhere(broken.vertices.size(), SurfacePoint{0, {1, 0, 0}});
  EXPECT_THROW(remesh_pair(broken, broken, anywhere, anywhere, {}, 100), TopologyError);
}

}  // namespace
}  // namespace cmaps
