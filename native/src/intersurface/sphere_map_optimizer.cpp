#include "intersurface/sphere_map_optimizer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "common/coloured_sweeps.h"
#include "common/corner_slots.h"
#include "common/triangle_neighbours.h"
#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/sphere_locator.h"
#include "intersurface/sphere_map_side.h"

namespace cmaps {

MapOptimizer::Side::Side(MapSide side)
    : surface(side.surface), sampled(side.sampled), sphere(side.sphere), fixed(std::move(side.fixed)),
      centres(std::move(side.centres)),
      neighbours(triangle_neighbours(surface.triangles)) {
  const size_t n = surface.vertices.size();
  if (sphere.size() != n || fixed.size() != n)
    throw InvalidInput("map optimizer: " + std::to_string(sphere.size()) + " sphere points and " +
                       std::to_string(fixed.size()) + " fixed flags for " + std::to_string(n) + " vertices");
  area = surface_area(TriangleMesh{surface.vertices, sampled});
  const double outwards = signed_volume(surface) < 0 ? -1 : 1;  // `surface` is closed: its holes have fans
  faces_of.resize(n);
  sampled_of.resize(n);
  slot.assign(n, -1);
  for (size_t f = 0; f < sampled.size(); ++f)
    for (int v : sampled[f]) {
      if (v < 0 || size_t(v) >= n)
        throw InvalidInput("map optimizer: sampled vertex " + std::to_string(v) + " out of range");
      sampled_of[v].push_back(int(f));
    }
  shapes.reserve(sampled.size());
  for (const Triangle& t : sampled)
    shapes.push_back(source_triangle({surface.vertices[t[0]], surface.vertices[t[1]], surface.vertices[t[2]]}));
  min_shape.resize(surface.triangles.size());
  normals.resize(surface.triangles.size());
  for (size_t f = 0; f < surface.triangles.size(); ++f) {
    const Triangle& t = surface.triangles[f];
    for (int v : t) faces_of[v].push_back(int(f));
    min_shape[f] = std::min(1e-3, 0.5 * spherical_shape(sphere[t[0]], sphere[t[1]], sphere[t[2]]));
    const Vec3& x = surface.vertices[t[0]];
    normals[f] = outwards * (surface.vertices[t[1]] - x).cross(surface.vertices[t[2]] - x).normalized();
  }
  // The input's order against the surface's: its triangles' normals against
  // the outward normals at their corners (an input with holes has no volume
  // whose sign could tell).
  double agreement = 0;
  for (const Triangle& t : sampled) {
    const Vec3& x = surface.vertices[t[0]];
    const Vec3 normal = (surface.vertices[t[1]] - x).cross(surface.vertices[t[2]] - x);
    for (int v : t)
      for (int f : faces_of[v]) agreement += normal.dot(normals[f]);
  }
  orientation = agreement < 0 ? -1 : 1;
  // A vertex move reads its sampled triangles' corners too, and a Steiner
  // vertex can part two corners of one: those must not move at once either.
  std::vector<Triangle> both = surface.triangles;
  both.insert(both.end(), sampled.begin(), sampled.end());
  colouring = colour_vertices(
      int(n), both, [](size_t) { return true; }, [this](int v) { return !fixed[v]; });
}

MapOptimizer::MapOptimizer(MapSide a, MapSide b, int threads)
    : a_(std::make_unique<Side>(std::move(a))), b_(std::make_unique<Side>(std::move(b))),
      threads_(std::max(1, threads)) {}

MapOptimizer::~MapOptimizer() = default;

void MapOptimizer::refresh(Side& moving, Side& other) {
  // In the pass before (if any) the moving side stayed put: its locator then serves again.
  const std::unique_ptr<SphereLocator> on_moving =
      on_other_ ? std::move(on_other_) : std::make_unique<SphereLocator>(moving.sphere, moving.surface.triangles);
  on_other_ = std::make_unique<SphereLocator>(other.sphere, other.surface.triangles);
  // Images of `from`'s vertices on `to`, scaled to `from`'s area.
  const auto images = [&](const Side& from, const Side& to, const std::vector<SphereLocation>& at) {
    const double scale = std::sqrt(from.area / to.area);
    std::vector<Image> result(at.size());
    parallel_for(at.size(), threads_,
                 [&](size_t i) { result[i] = to.image_in(at[i].triangle, at[i].barycentric.data(), scale); });
    return result;
  };
  moving.images = images(moving, other, on_other_->locate_all(moving.sphere, threads_));
  const std::vector<SphereLocation> at = on_moving->locate_all(other.sphere, threads_);
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
  std::vector<int> inside;
  for (int f : star) inside.insert(inside.end(), s.holds[f].begin(), s.holds[f].end());
  std::sort(inside.begin(), inside.end());
  const std::vector<int>& sampled = s.sampled_of[v];
  const std::vector<int> other_faces = o.around(o.sampled_of, inside);
  std::vector<std::array<int, 3>> other_slots;  // per corner of other_faces: its index in `inside`, -1 if not there
  for (int g : other_faces) other_slots.push_back(corner_slots(o.sampled[g], inside));
  std::vector<Image> inside_images(inside.size());
  std::vector<int> inside_faces(inside.size());
  const double to_moving = std::sqrt(o.area / s.area);

  // The energy with v at sphere point x (+inf outside the allowed kernel);
  // leaves v's image and those of the vertices inside in `image`, `inside_images`.
  Image image;
  const auto energy_at = [&](const Vec3& x) {
    const auto position = [&](int u) -> const Vec3& { return u == v ? x : s.sphere[u]; };
    for (int f : star) {
      const Triangle& t = s.surface.triangles[f];
      if (!(spherical_shape(position(t[0]), position(t[1]), position(t[2])) > s.min_shape[f])) return kInfinity;
    }
    const SphereLocation at = on_other_->locate(x);
    image = o.image_in(at.triangle, at.barycentric.data(), 1 / to_moving);
    for (size_t i = 0; i < inside.size(); ++i) {
      double w[3] = {1, 0, 0};
      inside_faces[i] = s.holder(o.sphere[inside[i]], star, position, w);
      if (inside_faces[i] < 0) return kInfinity;
      inside_images[i] = s.image_in(inside_faces[i], w, to_moving);
    }
    double energy = 0;
    for (int f : sampled)
      energy += s.triangle_energy(f, [&](int u) -> const Image& { return u == v ? image : s.images[u]; });
    for (std::size_t j = 0; j < other_faces.size(); ++j) {
      const std::array<int, 3>& slots = other_slots[j];
      const Triangle& t = o.sampled[other_faces[j]];
      const Image* image[3];
      for (int k = 0; k < 3; ++k) image[k] = slots[k] >= 0 ? &inside_images[slots[k]] : &o.images[t[k]];
      energy += o.energy_of_images(other_faces[j], image);
    }
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

void MapOptimizer::optimize(int rounds, int sweeps, double tolerance, bool with_regions,
                            const std::function<bool(double)>& keep_going) {
  const int passes = 2 * std::max(0, rounds);
  on_other_.reset();  // nothing carried over from a call cut short
  for (int pass = 0; pass < passes; ++pass) {
    Side& s = pass % 2 ? *b_ : *a_;
    Side& o = pass % 2 ? *a_ : *b_;
    refresh(s, o);
    bool going = true;
    const auto going_on = [&] { return going = !keep_going || keep_going(double(pass) / passes); };
    if (with_regions && pass < 2 && !regions(s, o, going_on)) break;
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
