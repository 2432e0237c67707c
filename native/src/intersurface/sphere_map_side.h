// One side of the map MapOptimizer lowers (sphere_map_optimizer.h): a surface,
// its sphere points, its vertices' images on the other surface and the other
// side's vertices each of its spherical triangles holds. Shared by the two
// kinds of moves: one vertex at a time (sphere_map_optimizer.cpp) and a whole
// region at once (sphere_region_moves.cpp).
#pragma once
#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "common/coloured_sweeps.h"
#include "intersurface/sphere_map_optimizer.h"
#include "intersurface/surface_image.h"
#include "intersurface/symmetric_dirichlet.h"

namespace cmaps {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A folded image triangle (facing against the surface it lies on) adds this
// energy density times the cosine of the angle between its normal and the
// surface's reversed: nothing at the onset of a fold, so the difference steps
// of a vertex move see a continuous energy that falls towards unfolding, and
// the full density when it faces straight against the surface, enough to pay
// for much distortion around it.
constexpr double kFoldDensity = 100;

// det(a, b, c) over the squared edge lengths: about 0.29 for an equilateral
// triangle, 0 for a degenerate one, negative for a flipped one.
inline double spherical_shape(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double edges = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return edges > 0 ? a.dot(b.cross(c)) / edges : 0;
}

// Barycentric coordinates of direction d in the chordal triangle (c0, c1,
// c2) by radial projection; the smallest one is returned (negative outside).
inline double radial_barycentric(const Vec3& d, const Vec3& c0, const Vec3& c1, const Vec3& c2, double (&w)[3]) {
  w[0] = d.dot(c1.cross(c2)), w[1] = d.dot(c2.cross(c0)), w[2] = d.dot(c0.cross(c1));
  const double sum = w[0] + w[1] + w[2];
  if (!(sum > 0)) return -kInfinity;
  for (double& x : w) x /= sum;
  return std::min({w[0], w[1], w[2]});
}

struct MapOptimizer::Side {
  const TriangleMesh& surface;
  const std::vector<Triangle>& sampled;
  std::vector<Vec3>& sphere;
  std::vector<char> fixed;
  std::vector<int> centres;
  double area = 0;
  std::vector<std::vector<int>> faces_of;    // per vertex: its triangles of `surface`
  std::vector<std::vector<int>> sampled_of;  // per vertex: its sampled triangles
  std::vector<SourceTriangle> shapes;        // per sampled triangle
  std::vector<std::array<int, 3>> neighbours;  // per triangle, across edge k (corner k to k + 1)
  std::vector<double> min_shape;               // per triangle: the thinnest shape allowed on the sphere
  // Per triangle: the unit normal, facing outwards (the spherical map may
  // list the triangles in the other order than the input).
  std::vector<Vec3> normals;
  double orientation = 1;  // -1 when the input lists its triangles inwards
  VertexColouring colouring;
  // Refreshed before each pass: every vertex's image on the other surface
  // (scaled to this side's area), pending images while the other side
  // moves, and per triangle the other side's vertices whose sphere points lie in it.
  std::vector<Image> images, pending;
  std::vector<std::vector<int>> holds;
  // During a region move: per vertex, its place among the vertices the move
  // carries (-1 for the rest).
  std::vector<int> slot;

  explicit Side(MapSide side);

  // The point with weights w in triangle f (negative weights taken as 0),
  // scaled by `scale`, as the image of a vertex of the other side.
  Image image_in(int f, const double* w, double scale) const {
    const Triangle& t = surface.triangles[f];
    Vec3 x = Vec3::Zero();
    double sum = 0;
    for (int k = 0; k < 3; ++k) x += std::max(0.0, w[k]) * surface.vertices[t[k]], sum += std::max(0.0, w[k]);
    return {scale * x / std::max(sum, 1e-300), normals[f]};
  }

  // Of `faces`, the triangle whose cone holds direction d best (its smallest
  // radial barycentric coordinate the largest), with `w` its coordinates and
  // position(u) the sphere point of vertex u; -1 if none faces d.
  template <class Position>
  int holder(const Vec3& d, const std::vector<int>& faces, const Position& position, double (&w)[3]) const {
    double best = -kInfinity, x[3];
    int found = -1;
    for (int f : faces) {
      const Triangle& t = surface.triangles[f];
      const double lowest = radial_barycentric(d, position(t[0]), position(t[1]), position(t[2]), x);
      if (lowest > best) best = lowest, found = f, std::copy(x, x + 3, w);
    }
    return found;
  }

  // The triangles of `of` (faces_of or sampled_of) around `vertices`, sorted, each once.
  std::vector<int> around(const std::vector<std::vector<int>>& of, const std::vector<int>& vertices) const {
    std::vector<int> faces;
    for (int v : vertices) faces.insert(faces.end(), of[v].begin(), of[v].end());
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
  }

  // Energy of sampled triangle f times its area over the side's area, a
  // fold charged up to kFoldDensity more; image_of(u) is the image of vertex u.
  template <class ImageOf>
  double triangle_energy(int f, const ImageOf& image_of) const {
    const Triangle& t = sampled[f];
    const Image* const image[3] = {&image_of(t[0]), &image_of(t[1]), &image_of(t[2])};
    return energy_of_images(f, image);
  }
  // The same with its corners' images given.
  double energy_of_images(int f, const Image* const (&image)[3]) const {
    const Vec3 q[3] = {image[0]->position, image[1]->position, image[2]->position};
    const SourceTriangle& p = shapes[f];
    if (!(p.area > 0)) return 0;
    const Vec3 nq = (q[1] - q[0]).cross(q[2] - q[0]);
    double e = symmetric_dirichlet(p, q, nq);
    const Vec3 normal = surface_normal(image);
    const double against = orientation * nq.dot(normal);
    if (against < 0) e -= kFoldDensity * against / (nq.norm() * normal.norm());
    return e * p.area / area;
  }
};

}  // namespace cmaps
