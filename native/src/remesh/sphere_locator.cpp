#include "consistent_maps/sphere_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/parallel_for.h"
#include "consistent_maps/errors.h"

namespace cmaps {
namespace {

// Cube face f = 2k + (negative side) looks along axis k; (u, v) are the
// gnomonic coordinates along axes k+1 and k+2, both in [-1, 1] on the face.
struct CubeFace {
  int k, i, j;
  double s;
};

CubeFace cube_face(int f) { return {f / 2, (f / 2 + 1) % 3, (f / 2 + 2) % 3, f % 2 ? -1.0 : 1.0}; }

// Pyramid planes are pushed out by this much (and boxes grown by it) so a
// direction on a face or cell boundary still finds its triangle in either cell.
constexpr double kSlack = 1e-9;

// Keeps the part of a convex planar polygon with m . p >= 0 (Sutherland-Hodgman).
void clip(std::vector<Vec3>& polygon, const Vec3& m, std::vector<Vec3>& scratch) {
  scratch.clear();
  for (size_t q = 0; q < polygon.size(); ++q) {
    const Vec3& p0 = polygon[q];
    const Vec3& p1 = polygon[(q + 1) % polygon.size()];
    const double s0 = m.dot(p0), s1 = m.dot(p1);
    if (s0 >= 0) scratch.push_back(p0);
    if ((s0 >= 0) != (s1 >= 0)) scratch.push_back(p0 + (p1 - p0) * (s0 / (s0 - s1)));
  }
  polygon.swap(scratch);
}

int cell_coordinate(double u, int resolution) {
  return std::clamp(static_cast<int>(std::floor((u + 1) * 0.5 * resolution)), 0, resolution - 1);
}

// The gnomonic image on `face` of the part of the cone over triangle
// (a, b, c) inside the face's (slightly widened) pyramid, as points (u, v, 1);
// empty when the cone misses the face.
void cone_image(const Vec3& a, const Vec3& b, const Vec3& c, const CubeFace& face, std::vector<Vec3>& image,
                std::vector<Vec3>& scratch) {
  image.clear();
  if (std::max({a[face.k], b[face.k], c[face.k]}) * face.s <= 0) return;
  std::vector<Vec3> polygon = {a, b, c};
  const Vec3 axis = Vec3::Unit(face.k) * face.s * (1 + kSlack);
  for (const Vec3& side : {Vec3(Vec3::Unit(face.i)), Vec3(Vec3::Unit(face.j))}) {
    clip(polygon, axis - side, scratch);
    clip(polygon, axis + side, scratch);
  }
  for (const Vec3& p : polygon) {
    const double depth = p[face.k] * face.s;
    if (!(depth > 0)) {  // only a cone reaching the origin gets here; take the whole face
      image = {Vec3(-2, -2, 1), Vec3(2, -2, 1), Vec3(2, 2, 1), Vec3(-2, 2, 1)};
      return;
    }
    image.emplace_back(p[face.i] / depth, p[face.j] / depth, 1);
  }
}

// Area of a convex image polygon inside the box [x0, x1] x [y0, y1]; -1 when
// they are disjoint (0 when they only touch).
double overlap_area(const std::vector<Vec3>& image, double x0, double x1, double y0, double y1,
                    std::vector<Vec3>& part, std::vector<Vec3>& scratch) {
  part = image;
  clip(part, Vec3(1, 0, -x0), scratch);
  clip(part, Vec3(-1, 0, x1), scratch);
  clip(part, Vec3(0, 1, -y0), scratch);
  clip(part, Vec3(0, -1, y1), scratch);
  if (part.empty()) return -1;
  double twice_area = 0;
  for (size_t q = 0; q < part.size(); ++q) {
    const Vec3 &a = part[q], &b = part[(q + 1) % part.size()];
    twice_area += a[0] * b[1] - a[1] * b[0];
  }
  return std::abs(twice_area) / 2;
}

// Signed distance-like score of d to the triangle: the smallest of its
// (scaled) distances to the three edge planes; >= 0 inside.
double containment_score(const Vec3& d, const Vec3 (&n)[3]) {
  double score = std::numeric_limits<double>::infinity();
  for (const Vec3& e : n) {
    const double len = e.norm();
    score = std::min(score, len > 0 ? d.dot(e) / len : 0.0);
  }
  return score;
}

}  // namespace

SphereLocator::SphereLocator(std::vector<Vec3> sphere, std::vector<Triangle> triangles)
    : sphere_(std::move(sphere)), triangles_(std::move(triangles)) {
  if (triangles_.empty()) throw InvalidInput("sphere locator: no triangles");
  for (size_t v = 0; v < sphere_.size(); ++v) {
    const double len = sphere_[v].norm();
    if (!std::isfinite(len) || std::abs(len - 1) > 1e-6)
      throw InvalidInput("sphere locator: vertex " + std::to_string(v) + " is not a unit vector");
  }
  edge_normals_.resize(triangles_.size());
  std::vector<int> indexed;  // zero-area triangles contain no ray and are left out of the cells
  for (size_t t = 0; t < triangles_.size(); ++t) {
    for (int c : triangles_[t])
      if (c < 0 || c >= static_cast<int>(sphere_.size()))
        throw InvalidInput("sphere locator: triangle " + std::to_string(t) + " refers to vertex " +
                           std::to_string(c) + " of " + std::to_string(sphere_.size()));
    const Vec3 &a = sphere_[triangles_[t][0]], &b = sphere_[triangles_[t][1]], &c = sphere_[triangles_[t][2]];
    edge_normals_[t] = {{b.cross(c), c.cross(a), a.cross(b)}};
    const double det = a.dot(edge_normals_[t].n[0]);
    if (det < 0)
      throw InvalidInput("sphere locator: triangle " + std::to_string(t) + " is flipped on the sphere");
    if (det > 0) indexed.push_back(static_cast<int>(t));
  }
  if (indexed.empty()) throw InvalidInput("sphere locator: every triangle has zero area");

  // About two cells per triangle: few candidates per query, modest memory.
  resolution_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(indexed.size() / 3.0))));
  const int cells = 6 * resolution_ * resolution_;

  // Each triangle's cone is clipped to each face's pyramid and projected
  // gnomonically; every cell its image overlaps lists it, largest overlap
  // first, so the first candidate tested is usually the answer.
  struct Entry {
    int cell;
    double overlap;
    int triangle;
  };
  std::vector<Entry> entries;
  std::vector<Vec3> image, part, scratch;
  const double width = 2.0 / resolution_;
  for (int t : indexed) {
    const Triangle& corners = triangles_[t];
    for (int f = 0; f < 6; ++f) {
      cone_image(sphere_[corners[0]], sphere_[corners[1]], sphere_[corners[2]], cube_face(f), image, scratch);
      if (image.empty()) continue;
      double u0 = 1, u1 = -1, v0 = 1, v1 = -1;
      for (const Vec3& p : image) {
        u0 = std::min(u0, p[0]), u1 = std::max(u1, p[0]);
        v0 = std::min(v0, p[1]), v1 = std::max(v1, p[1]);
      }
      const int cu1 = cell_coordinate(u1 + kSlack, resolution_), cv1 = cell_coordinate(v1 + kSlack, resolution_);
      for (int cu = cell_coordinate(u0 - kSlack, resolution_); cu <= cu1; ++cu) {
        for (int cv = cell_coordinate(v0 - kSlack, resolution_); cv <= cv1; ++cv) {
          const double x0 = -1 + cu * width - kSlack, y0 = -1 + cv * width - kSlack;
          const double area = overlap_area(image, x0, x0 + width + 2 * kSlack, y0, y0 + width + 2 * kSlack, part,
                                           scratch);
          if (area >= 0) entries.push_back({(f * resolution_ + cu) * resolution_ + cv, area, t});
        }
      }
    }
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.overlap > b.overlap;
  });
  cell_start_.assign(cells + 1, 0);
  for (const Entry& e : entries) ++cell_start_[e.cell + 1];
  for (int c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_triangles_.resize(entries.size());
  for (size_t e = 0; e < entries.size(); ++e) cell_triangles_[e] = entries[e].triangle;
}

int SphereLocator::cell_of(const Vec3& d) const {
  const Vec3 m = d.cwiseAbs();
  const int k = m[0] >= m[1] ? (m[0] >= m[2] ? 0 : 2) : (m[1] >= m[2] ? 1 : 2);
  const int f = 2 * k + (d[k] < 0);
  const double inverse = 1 / m[k];
  const int u = cell_coordinate(d[(k + 1) % 3] * inverse, resolution_);
  const int v = cell_coordinate(d[(k + 2) % 3] * inverse, resolution_);
  return (f * resolution_ + u) * resolution_ + v;
}

int SphereLocator::checked_cell_of(const Vec3& d) const {
  if (!d.allFinite() || d.isZero(0)) throw InvalidInput("locate: direction must be non-zero and finite");
  return cell_of(d);
}

SphereLocation SphereLocator::locate(const Vec3& d) const { return locate_in_cell(d, checked_cell_of(d)); }

SphereLocation SphereLocator::locate_in_cell(const Vec3& d, int cell) const {
  auto result = [&](int t, double w0, double w1, double w2) {
    // Clamp rounding-level negatives of boundary points; sum > 0 was checked.
    w0 = std::max(w0, 0.0), w1 = std::max(w1, 0.0), w2 = std::max(w2, 0.0);
    const double sum = w0 + w1 + w2;
    return SphereLocation{t, {w0 / sum, w1 / sum, w2 / sum}};
  };
  const int* begin = cell_triangles_.data() + cell_start_[cell];
  const int* end = cell_triangles_.data() + cell_start_[cell + 1];
  for (const int* it = begin; it != end; ++it) {
    const Vec3(&n)[3] = edge_normals_[*it].n;
    const double w0 = d.dot(n[0]), w1 = d.dot(n[1]), w2 = d.dot(n[2]);
    if (w0 >= 0 && w1 >= 0 && w2 >= 0 && w0 + w1 + w2 > 0) return result(*it, w0, w1, w2);
  }
  // Rounding put d just outside every candidate (a point on an edge or
  // vertex, or a sliver): take the candidate it is least outside of, and
  // should the cell hold nothing usable, the best triangle of all.
  auto best_of = [&](auto&& triangles_to_try) {
    int best = -1;
    double best_score = -std::numeric_limits<double>::infinity();
    triangles_to_try([&](int t) {
      const Vec3(&n)[3] = edge_normals_[t].n;
      if (d.dot(n[0] + n[1] + n[2]) <= 0) return;
      const double score = containment_score(d, n);
      if (score > best_score) best_score = score, best = t;
    });
    return best;
  };
  int best = best_of([&](auto&& visit) {
    for (const int* it = begin; it != end; ++it) visit(*it);
  });
  if (best < 0)
    best = best_of([&](auto&& visit) {
      for (size_t t = 0; t < triangles_.size(); ++t) visit(static_cast<int>(t));
    });
  if (best < 0) throw InvalidInput("locate: the triangles do not cover the direction");
  const Vec3(&n)[3] = edge_normals_[best].n;
  return result(best, d.dot(n[0]), d.dot(n[1]), d.dot(n[2]));
}

std::vector<SphereLocation> SphereLocator::locate_all(const std::vector<Vec3>& directions, int threads) const {
  std::vector<SphereLocation> out(directions.size());
  // Blocks of queries go through the lookups in stages, prefetching each
  // stage's memory for the whole block first, so the cache misses of
  // different queries overlap instead of queueing (2-3x faster than one by one).
  constexpr size_t kBlock = 64;
  parallel_for((directions.size() + kBlock - 1) / kBlock, threads, [&](size_t block) {
    const size_t begin = block * kBlock, count = std::min(kBlock, directions.size() - begin);
    int cells[kBlock];
    for (size_t q = 0; q < count; ++q) {
      cells[q] = checked_cell_of(directions[begin + q]);
      __builtin_prefetch(&cell_start_[cells[q]]);
    }
    for (size_t q = 0; q < count; ++q) __builtin_prefetch(&cell_triangles_[cell_start_[cells[q]]]);
    for (size_t q = 0; q < count; ++q) {
      const char* first = reinterpret_cast<const char*>(&edge_normals_[cell_triangles_[cell_start_[cells[q]]]]);
      __builtin_prefetch(first);
      __builtin_prefetch(first + sizeof(EdgeNormals) - 1);
    }
    for (size_t q = 0; q < count; ++q) out[begin + q] = locate_in_cell(directions[begin + q], cells[q]);
  }, 16);
  return out;
}

void SphereLocator::check_values(size_t rows) const {
  if (rows != sphere_.size())
    throw InvalidInput("interpolate: got values for " + std::to_string(rows) + " vertices, the locator has " +
                       std::to_string(sphere_.size()));
}

const Triangle& SphereLocator::corners(const SphereLocation& location) const {
  if (location.triangle < 0 || location.triangle >= static_cast<int>(triangles_.size()))
    throw InvalidInput("interpolate: location refers to triangle " + std::to_string(location.triangle) + " of " +
                       std::to_string(triangles_.size()));
  return triangles_[location.triangle];
}

RowMatrixXd SphereLocator::interpolate(const RowMatrixXd& values, const std::vector<SphereLocation>& at,
                                       int threads) const {
  check_values(values.rows());
  RowMatrixXd out(at.size(), values.cols());
  parallel_for(at.size(), threads, [&](size_t q) {
    const Triangle& t = corners(at[q]);
    const auto& w = at[q].barycentric;
    out.row(q) = w[0] * values.row(t[0]) + w[1] * values.row(t[1]) + w[2] * values.row(t[2]);
  }, 1024);
  return out;
}

std::vector<double> SphereLocator::interpolate(const std::vector<double>& values, int stride,
                                               const std::vector<SphereLocation>& at, int threads) const {
  if (stride <= 0 || values.size() % stride != 0)
    throw InvalidInput("interpolate: value count " + std::to_string(values.size()) +
                       " is not a multiple of the stride " + std::to_string(stride));
  check_values(values.size() / stride);
  std::vector<double> out(at.size() * stride);
  parallel_for(at.size(), threads, [&](size_t q) {
    const Triangle& t = corners(at[q]);
    const auto& w = at[q].barycentric;
    for (int c = 0; c < stride; ++c)
      out[q * stride + c] = w[0] * values[t[0] * size_t(stride) + c] + w[1] * values[t[1] * size_t(stride) + c] +
                            w[2] * values[t[2] * size_t(stride) + c];
  }, 1024);
  return out;
}

std::vector<Vec3> SphereLocator::interpolate(const std::vector<Vec3>& values, const std::vector<SphereLocation>& at,
                                             int threads) const {
  check_values(values.size());
  std::vector<Vec3> out(at.size());
  parallel_for(at.size(), threads, [&](size_t q) {
    const Triangle& t = corners(at[q]);
    const auto& w = at[q].barycentric;
    out[q] = w[0] * values[t[0]] + w[1] * values[t[1]] + w[2] * values[t[2]];
  }, 1024);
  return out;
}

}  // namespace cmaps
