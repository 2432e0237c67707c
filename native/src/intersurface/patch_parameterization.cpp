#include "intersurface/patch_parameterization.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/parallel_for.h"
#include "consistent_maps/intersurface_map.h"
#include "intersurface/chord_energy.h"
#include "intersurface/patch_embedding.h"
#include "intersurface/patch_locator.h"

namespace cmaps {
namespace {

// Splits every non-path edge whose ends both lie on paths, keeping `patch`
// (per triangle) in step with the new triangles.
void split_chords(PartitionSide& side) {
  std::vector<char> on_path(side.mesh.vertex_count(), 0);
  std::vector<char> path_edge(side.mesh.edge_count(), 0);
  for (const auto& path : side.paths) {
    for (int v : path) on_path[v] = 1;
    for (size_t i = 0; i + 1 < path.size(); ++i) path_edge[side.mesh.edge(path[i], path[i + 1])] = 1;
  }
  const int edges = side.mesh.edge_count();
  for (int e = 0; e < edges; ++e) {
    const auto [u, w] = side.mesh.edge_vertices(e);
    if (u < 0 || path_edge[e] || !on_path[u] || !on_path[w]) continue;
    const auto faces = side.mesh.edge_faces(e);
    side.mesh.split_edge(e);
    side.patch.push_back(side.patch[faces[0]]);
    side.patch.push_back(side.patch[faces[1]]);
  }
}

// The patch's L2 stretch (Sander et al. 2001), and with `per_vertex` each
// vertex's over its triangles. Infinite when a triangle is degenerate in the
// canonical triangle.
double stretch_of(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv, const std::vector<int>& faces,
                  std::unordered_map<int, double>* per_vertex) {
  std::unordered_map<int, double> sum, area;
  double all = 0, all_area = 0;
  for (int f : faces) {
    const Triangle& t = side.mesh.triangles()[f];
    const Vec3 q[3] = {side.mesh.position(t[0]), side.mesh.position(t[1]), side.mesh.position(t[2])};
    const Vec2 p[3] = {uv.at(t[0]), uv.at(t[1]), uv.at(t[2])};
    const double a2 = 0.5 * ((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
    const double a3 = 0.5 * (q[1] - q[0]).cross(q[2] - q[0]).norm();
    double squared = std::numeric_limits<double>::infinity();
    if (std::abs(a2) > 0) {
      const Vec3 ss =
          (q[0] * (p[1].y() - p[2].y()) + q[1] * (p[2].y() - p[0].y()) + q[2] * (p[0].y() - p[1].y())) / (2 * a2);
      const Vec3 st =
          (q[0] * (p[2].x() - p[1].x()) + q[1] * (p[0].x() - p[2].x()) + q[2] * (p[1].x() - p[0].x())) / (2 * a2);
      squared = 0.5 * (ss.squaredNorm() + st.squaredNorm());
    }
    all += a3 * squared, all_area += a3;
    if (per_vertex)
      for (int v : t) sum[v] += a3 * squared, area[v] += a3;
  }
  if (per_vertex) {
    for (auto& [v, x] : sum) x = area[v] > 0 ? std::sqrt(x / area[v]) : 1;
    *per_vertex = std::move(sum);
  }
  return all_area > 0 ? std::sqrt(all / all_area) : 0;
}

// Canonical points of one patch: its boundary by arc length, its interior
// by mean-value weights, then stretch reweighting: each round divides every
// weight by the stretch at the neighbour it points to and solves again, so
// crowded regions (a protrusion squeezed into a corner of the triangle) open
// up. Weights stay positive, so every round is a bijective embedding. `pull`
// gets each vertex's product of the divisors kept.
std::unordered_map<int, Vec2> parameterize(const PartitionSide& side, const BaseTriangle& base,
                                           const std::vector<int>& faces, int stretch_rounds,
                                           std::unordered_map<int, double>& pull) {
  std::unordered_map<int, Vec2> uv;
  for (int k = 0; k < 3; ++k) {
    std::vector<int> path = side.paths[base.edges[k]];
    if (base.reversed[k]) std::reverse(path.begin(), path.end());
    std::vector<double> at{0};
    for (size_t i = 1; i < path.size(); ++i)
      at.push_back(at.back() + (side.mesh.position(path[i]) - side.mesh.position(path[i - 1])).norm());
    for (size_t i = 0; i < path.size(); ++i) {
      const double t = at.back() > 0 ? at[i] / at.back() : double(i) / (path.size() - 1);
      uv[path[i]] = (1 - t) * kCanonicalCorner[k] + t * kCanonicalCorner[(k + 1) % 3];
    }
  }
  PatchEmbedding embedding(side, faces, uv);
  if (embedding.empty()) return uv;
  PatchEmbedding::Weights weight = embedding.mean_value_weights();
  embedding.solve(weight);
  std::unordered_map<int, double> sigma;
  double stretch = stretch_of(side, uv, faces, &sigma);
  for (auto& [v, s] : sigma) pull[v] = 1;
  for (int round = 0; round < stretch_rounds && std::isfinite(stretch); ++round) {
    const std::unordered_map<int, Vec2> kept = uv;
    for (auto& row : weight)
      for (auto& [v, w] : row) w /= std::max(sigma.at(v), 1e-12);
    embedding.solve(weight);
    std::unordered_map<int, double> next_sigma;
    const double next = stretch_of(side, uv, faces, &next_sigma);
    if (!(next < stretch)) {
      uv = kept;
      break;
    }
    for (auto& [v, p] : pull) p /= std::max(sigma.at(v), 1e-12);
    stretch = next, sigma = std::move(next_sigma);
  }
  return uv;
}

}  // namespace

InputLocation to_input(const PartitionSide& side, const TriangleMesh& input, int face, const std::array<double, 3>& w) {
  InputLocation p;
  p.triangle = side.mesh.input_triangle(face);
  const Triangle& corners = input.triangles[p.triangle];
  double stray = 0;
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const InputPoint& origin = side.mesh.surface_point(side.mesh.triangles()[face][k]);
    for (int j = 0; j < 3; ++j) {
      const int v = origin.vertices[j];
      if (v < 0) continue;
      const double weight = w[k] * origin.weights[j];
      x += weight * input.vertices[v];
      const int slot = int(std::find(corners.begin(), corners.end(), v) - corners.begin());
      if (slot < 3) p.barycentric[slot] += weight;
      else stray += std::abs(weight);
    }
  }
  if (stray > 1e-12) {  // never, up to the refinement's bookkeeping: project onto the triangle
    const Vec3& a = input.vertices[corners[0]];
    const Vec3 e1 = input.vertices[corners[1]] - a, e2 = input.vertices[corners[2]] - a;
    const double aa = e1.dot(e1), ab = e1.dot(e2), bb = e2.dot(e2), det = aa * bb - ab * ab;
    const Vec3 d = x - a;
    const double s = det > 0 ? (bb * d.dot(e1) - ab * d.dot(e2)) / det : 0;
    const double t = det > 0 ? (aa * d.dot(e2) - ab * d.dot(e1)) / det : 0;
    p.barycentric = {1 - s - t, s, t};
  }
  double sum = 0;
  for (double& b : p.barycentric) sum += (b = std::max(0.0, b));
  for (double& b : p.barycentric) b = sum > 0 ? b / sum : 1.0 / 3;
  return p;
}

std::vector<std::vector<int>> faces_by_patch(const PartitionSide& side, int patches) {
  std::vector<std::vector<int>> faces(patches);
  for (int f = 0; f < int(side.patch.size()); ++f) faces[side.patch[f]].push_back(f);
  return faces;
}

int turned_in_patches(const PartitionSide& side, const PatchParameterization& uv) {
  int turned = 0;
  const std::vector<std::vector<int>> faces = faces_by_patch(side, int(uv.uv.size()));
  for (std::size_t t = 0; t < faces.size(); ++t) {
    std::vector<double> area;
    double total = 0;
    for (int f : faces[t]) {
      if (side.in_fan(f)) continue;
      const Triangle& c = side.mesh.triangles()[f];
      area.push_back(twice_signed_area(uv.uv[t].at(c[0]), uv.uv[t].at(c[1]), uv.uv[t].at(c[2])));
      total += area.back();
    }
    for (double a : area) turned += !(a * total > 0);
  }
  return turned;
}

PatchParameterization parameterize_patches(PartitionSide& side, const ConsistentPartition& partition,
                                           int stretch_rounds) {
  split_chords(side);
  const int patches = int(partition.triangles.size());
  const std::vector<std::vector<int>> faces = faces_by_patch(side, patches);
  PatchParameterization result;
  result.uv.resize(patches);
  result.pull.resize(patches);
  parallel_for(patches, 2, [&](int t) {
    result.uv[t] = parameterize(side, partition.triangles[t], faces[t], stretch_rounds, result.pull[t]);
  });
  return result;
}

double patch_stretch(const PartitionSide& side, const std::unordered_map<int, Vec2>& uv,
                     const std::vector<int>& faces) {
  return stretch_of(side, uv, faces, nullptr);
}

void snap_features(const PartitionSide& source, const PartitionSide& target, const TriangleMesh& target_input,
                   std::vector<InputLocation>& image) {
  const int n = source.mesh.input_vertex_count();
  std::vector<int> incident(target_input.vertices.size(), -1);
  for (int t = 0; t < int(target_input.triangles.size()); ++t)  // surface triangles before fan triangles
    for (int v : target_input.triangles[t])
      if (incident[v] < 0) incident[v] = t;
  for (size_t f = 0; f < source.feature_vertex.size(); ++f) {
    const int from = source.feature_vertex[f], to = target.feature_vertex[f];
    if (from >= n || to >= target.mesh.input_vertex_count()) continue;
    InputLocation& p = image[from];
    p.triangle = incident[to];
    for (int j = 0; j < 3; ++j) p.barycentric[j] = target_input.triangles[p.triangle][j] == to ? 1 : 0;
  }
}

std::vector<RefinedPoint> corner_points(const PartitionSide& source, const TriangleMesh& source_input, int threads) {
  const int triangles = int(source_input.triangles.size());
  std::vector<std::vector<int>> refined(triangles);  // per input triangle: the refined faces inside it
  for (int f = 0; f < int(source.mesh.triangles().size()); ++f) refined[source.mesh.input_triangle(f)].push_back(f);
  std::vector<RefinedPoint> points(3 * std::size_t(triangles));
  parallel_for(triangles, threads, [&](int t) {
    // t's refined faces in an affine chart of t: a point's weights on t's corners 1 and 2.
    const Triangle& corners = source_input.triangles[t];
    std::unordered_map<int, Vec2> chart;
    for (int f : refined[t])
      for (int v : source.mesh.triangles()[f]) {
        const InputPoint& origin = source.mesh.surface_point(v);
        Vec2& q = chart[v] = Vec2::Zero();
        for (int j = 0; j < 3; ++j)
          for (int k = 1; k < 3; ++k)
            if (origin.vertices[j] == corners[k]) q[k - 1] += origin.weights[j];
      }
    const PatchLocator locator(source, chart, refined[t]);
    for (int k = 0; k < 3; ++k) {
      Vec2 p = Vec2::Constant(kCornerNudge);
      if (k > 0) p[k - 1] = 1 - 2 * kCornerNudge;
      const auto [face, w] = locator.locate(p);
      points[3 * std::size_t(t) + k] = {face, w};
    }
  });
  return points;
}

}  // namespace cmaps
