#include "intersurface/sphere_map_optimizer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/coloured_sweeps.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/sphere_locator.h"
#include "intersurface/symmetric_dirichlet.h"

namespace cmaps {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// det(a, b, c) over the squared edge lengths: about 0.29 for an equilateral
// triangle, 0 for a degenerate one, negative for a flipped one.
double shape(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double edges = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return edges > 0 ? a.dot(b.cross(c)) / edges : 0;
}

// Barycentric coordinates of direction d in the chordal triangle (c0, c1,
// c2) by radial projection; the smallest one is returned (negative outside).
double radial_barycentric(const Vec3& d, const Vec3& c0, const Vec3& c1, const Vec3& c2, double (&w)[3]) {
  w[0] = d.dot(c1.cross(c2)), w[1] = d.dot(c2.cross(c0)), w[2] = d.dot(c0.cross(c1));
  const double sum = w[0] + w[1] + w[2];
  if (!(sum > 0)) return -kInfinity;
  for (double& x : w) x /= sum;
  return std::min({w[0], w[1], w[2]});
}

}  // namespace

struct MapOptimizer::Side {
  const TriangleMesh& surface;
  std::vector<Vec3>& sphere;
  std::vector<char> fixed;
  double area = 0;
  std::vector<std::vector<int>> faces_of;
  std::vector<double> min_shape;  // per triangle: the thinnest shape allowed on the sphere
  VertexColouring colouring;
  // Refreshed before each pass: every vertex's image on the other surface
  // (scaled to this side's area), pending images while the other side
  // moves, and per triangle the other side's vertices whose sphere points lie in it.
  std::vector<Vec3> images, pending;
  std::vector<std::vector<int>> holds;

  explicit Side(MapSide side) : surface(side.surface), sphere(side.sphere), fixed(std::move(side.fixed)) {
    const size_t n = surface.vertices.size();
    if (sphere.size() != n || fixed.size() != n)
      throw InvalidInput("map optimizer: " + std::to_string(sphere.size()) + " sphere points and " +
                         std::to_string(fixed.size()) + " fixed flags for " + std::to_string(n) + " vertices");
    area = surface_area(surface);
    faces_of.resize(n);
    min_shape.resize(surface.triangles.size());
    for (size_t f = 0; f < surface.triangles.size(); ++f) {
      const Triangle& t = surface.triangles[f];
      for (int v : t) faces_of[v].push_back(int(f));
      min_shape[f] = std::min(1e-3, 0.5 * shape(sphere[t[0]], sphere[t[1]], sphere[t[2]]));
    }
    colouring = colour_vertices(
        int(n), surface.triangles, [](size_t) { return true; }, [this](int v) { return !fixed[v]; });
  }

  // Energy of triangle f times its area over the side's area; image(u) is
  // the image of vertex u.
  template <class Image>
  double triangle_energy(int f, const Image& image) const {
    const Triangle& t = surface.triangles[f];
    const Vec3 p[3] = {surface.vertices[t[0]], surface.vertices[t[1]], surface.vertices[t[2]]};
    const Vec3 q[3] = {image(t[0]), image(t[1]), image(t[2])};
    double a;
    const double e = symmetric_dirichlet(p, q, &a);
    return a > 0 ? e * a / area : 0;
  }
};

MapOptimizer::MapOptimizer(MapSide a, MapSide b, int threads)
    : a_(std::make_unique<Side>(std::move(a))), b_(std::make_unique<Side>(std::move(b))),
      threads_(std::max(1, threads)) {}

MapOptimizer::~MapOptimizer() = default;

void MapOptimizer::refresh(Side& moving, Side& other) {
  on_other_ = std::make_unique<SphereLocator>(other.sphere, other.surface.triangles);
  const SphereLocator on_moving(moving.sphere, moving.surface.triangles);
  // Images of `from`'s vertices on `to`, scaled to `from`'s area.
  const auto images = [&](const Side& from, const Side& to, const std::vector<SphereLocation>& at) {
    const double scale = std::sqrt(from.area / to.area);
    std::vector<Vec3> result(at.size());
    parallel_for(at.size(), threads_, [&](size_t i) {
      const Triangle& t = to.surface.triangles[at[i].triangle];
      Vec3 x = Vec3::Zero();
      for (int k = 0; k < 3; ++k) x += at[i].barycentric[k] * to.surface.vertices[t[k]];
      result[i] = scale * x;
    });
    return result;
  };
  moving.images = images(moving, other, on_other_->locate_all(moving.sphere, threads_));
  const std::vector<SphereLocation> at = on_moving.locate_all(other.sphere, threads_);
  other.images = other.pending = images(other, moving, at);
  moving.holds.assign(moving.surface.triangles.size(), {});
  for (size_t w = 0; w < at.size(); ++w) moving.holds[at[w].triangle].push_back(int(w));
}

double MapOptimizer::move(Side& s, Side& o, int v) const {
  if (s.fixed[v]) return 0;
  const Vec3 p = s.sphere[v];
  const std::vector<int>& star = s.faces_of[v];
  // As in the stretch optimizer: the longest chord to a neighbour caps the
  // step, the distance to the kernel's nearest bounding great circle sets the
  // difference step and the smallest move worth trying.
  double reach = 0, clearance = kInfinity;
  for (int f : star) {
    const Triangle& t = s.surface.triangles[f];
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const Vec3 &a = s.sphere[t[(k + 1) % 3]], &b = s.sphere[t[(k + 2) % 3]];
    reach = std::max(reach, (a - p).norm());
    const Vec3 normal = a.cross(b);
    clearance = std::min(clearance, p.dot(normal) / normal.norm());
  }
  if (!(clearance > 0) || !std::isfinite(reach)) return 0;
  const double scale = std::min(reach, clearance);

  // The other side's vertices inside the star (sorted, for lookups) and the
  // triangles around them: moving v moves their images too.
  std::vector<int> inside, other_faces;
  for (int f : star) inside.insert(inside.end(), s.holds[f].begin(), s.holds[f].end());
  std::sort(inside.begin(), inside.end());
  for (int w : inside) other_faces.insert(other_faces.end(), o.faces_of[w].begin(), o.faces_of[w].end());
  std::sort(other_faces.begin(), other_faces.end());
  other_faces.erase(std::unique(other_faces.begin(), other_faces.end()), other_faces.end());
  std::vector<Vec3> inside_images(inside.size());
  std::vector<int> inside_faces(inside.size());
  const double to_moving = std::sqrt(o.area / s.area);

  // The energy with v at sphere point x (+inf outside the allowed kernel);
  // leaves v's image and those of the vertices inside in `image`, `inside_images`.
  Vec3 image;
  const auto corner = [&](const Triangle& t, int k, const Vec3& x) -> const Vec3& {
    return t[k] == v ? x : s.sphere[t[k]];
  };
  const auto energy_at = [&](const Vec3& x) {
    for (int f : star) {
      const Triangle& t = s.surface.triangles[f];
      if (!(shape(corner(t, 0, x), corner(t, 1, x), corner(t, 2, x)) > s.min_shape[f])) return kInfinity;
    }
    const SphereLocation at = on_other_->locate(x);
    const Triangle& hit = o.surface.triangles[at.triangle];
    image = Vec3::Zero();
    for (int k = 0; k < 3; ++k) image += at.barycentric[k] * o.surface.vertices[hit[k]];
    image *= 1 / to_moving;
    for (size_t i = 0; i < inside.size(); ++i) {
      const Vec3& d = o.sphere[inside[i]];
      double best = -kInfinity, w[3], best_w[3] = {1, 0, 0};
      for (int f : star) {
        const Triangle& t = s.surface.triangles[f];
        const double lowest = radial_barycentric(d, corner(t, 0, x), corner(t, 1, x), corner(t, 2, x), w);
        if (lowest > best) best = lowest, inside_faces[i] = f, std::copy(w, w + 3, best_w);
      }
      const Triangle& t = s.surface.triangles[inside_faces[i]];
      Vec3 y = Vec3::Zero();
      for (int k = 0; k < 3; ++k) y += std::max(0.0, best_w[k]) * s.surface.vertices[t[k]];
      inside_images[i] = to_moving * y / std::max(1e-300, std::max(0.0, best_w[0]) + std::max(0.0, best_w[1]) +
                                                             std::max(0.0, best_w[2]));
    }
    double energy = 0;
    for (int f : star)
      energy += s.triangle_energy(f, [&](int u) -> const Vec3& { return u == v ? image : s.images[u]; });
    for (int g : other_faces)
      energy += o.triangle_energy(g, [&](int u) -> const Vec3& {
        const auto it = std::lower_bound(inside.begin(), inside.end(), u);
        return it != inside.end() && *it == u ? inside_images[it - inside.begin()] : o.images[u];
      });
    return energy;
  };

  const Vec3 t1 = p.unitOrthogonal(), t2 = p.cross(t1);
  const auto point = [&](double x, double y) { return Vec3((p + x * t1 + y * t2).normalized()); };
  const double h = 1e-3 * scale;
  const double e0 = energy_at(p);
  const double ex = energy_at(point(h, 0)), ex_ = energy_at(point(-h, 0));
  const double ey = energy_at(point(0, h)), ey_ = energy_at(point(0, -h));
  const double exy = energy_at(point(h, h)), ex_y_ = energy_at(point(-h, -h));
  const double exy_ = energy_at(point(h, -h)), ex_y = energy_at(point(-h, h));
  for (double e : {e0, ex, ex_, ey, ey_, exy, ex_y_, exy_, ex_y})
    if (!std::isfinite(e)) return 0;
  const Eigen::Vector2d g((ex - ex_) / (2 * h), (ey - ey_) / (2 * h));
  if (g.norm() == 0) return 0;
  Eigen::Matrix2d hessian;
  hessian(0, 0) = (ex - 2 * e0 + ex_) / (h * h);
  hessian(1, 1) = (ey - 2 * e0 + ey_) / (h * h);
  hessian(0, 1) = hessian(1, 0) = (exy - exy_ - ex_y + ex_y_) / (4 * h * h);
  Eigen::Vector2d step;
  if (hessian.determinant() > 0 && hessian.trace() > 0)
    step = -hessian.inverse() * g;
  else
    step = -g * (0.25 * reach / g.norm());
  if (step.norm() > 0.5 * reach) step *= 0.5 * reach / step.norm();

  const double slope = g.dot(step);
  for (double t = 1; t * step.norm() > 1e-3 * scale; t *= 0.5) {
    const Vec3 x = point(t * step.x(), t * step.y());
    if (!(energy_at(x) <= e0 + 1e-4 * t * slope)) continue;
    // Accepted: v, its image, and the other side's vertices inside the star
    // (their images wait in `pending` until the colour class is done).
    s.sphere[v] = x;
    s.images[v] = image;
    for (int f : star) s.holds[f].clear();
    for (size_t i = 0; i < inside.size(); ++i) {
      o.pending[inside[i]] = inside_images[i];
      s.holds[inside_faces[i]].push_back(inside[i]);
    }
    return (x - p).norm() / scale;
  }
  return 0;
}

void MapOptimizer::optimize(int rounds, int sweeps, double tolerance, const std::function<bool(double)>& keep_going) {
  const int passes = 2 * std::max(0, rounds);
  for (int pass = 0; pass < passes; ++pass) {
    Side& s = pass % 2 ? *b_ : *a_;
    Side& o = pass % 2 ? *a_ : *b_;
    refresh(s, o);
    bool going = true;
    coloured_sweeps(
        s.colouring, threads_, sweeps, tolerance, [&](int v) { return move(s, o, v); },
        [&](int sweep) {
          return going = !keep_going || keep_going((pass + double(sweep) / sweeps) / passes);
        },
        [&](const std::vector<int>& members) {
          for (int v : members)
            for (int f : s.faces_of[v])
              for (int w : s.holds[f]) o.images[w] = o.pending[w];
        });
    if (!going) break;
  }
  on_other_.reset();
}

}  // namespace cmaps
