// Region moves of the spherical map optimizer (sphere_map_optimizer.h): a
// smooth deformation of one side's sphere points inside a spherical cap.
//
// Vertex moves alone leave a part whose image is far too small or too large
// as it is (the cow's tail squeezed into the horse's rump): each vertex is
// held by its neighbours, and the whole part would have to move at once. In
// the cap of angular radius R around centre c, a point at tangent
// coordinates u (the logarithm map at c) goes to
//     u + b(|u| / R) (a u + R t),   b(r) = (1 - r^2)^2,
// a scaling by 1 + a at the centre and a shift by R t, both fading to
// nothing at the rim, so the union of the triangles the cap's vertices touch
// stays put. Fixed vertices (features) inside stay where they are; the
// triangle check keeps the others from crossing them. The three parameters
// (t, a) take one gradient step (central differences) with a backtracking
// line search, repeated while the energy drops; caps run from a radius of 1
// radian down to a sixteenth, centres evenly spread. Then caps centred where
// evenly spread ones fall short, down to a 256th of a radian: on each
// feature, which such caps cannot scale about (it stays put, so they would
// push its neighbours over it; a cap centred on it only scales, t = 0), and
// on the most distorted triangles, whose trouble is often finer than a
// sixteenth (the tip of the cow's tail, 300 times too small on the horse).
// (Session 11 tried shifts alone, one step per cap at three radii, and did
// not keep them: BENCHMARKS.md.)
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "consistent_maps/sphere_locator.h"
#include "intersurface/sphere_map_side.h"

namespace cmaps {
namespace {

constexpr int kLevels = 5;   // cap radii 1, 1/2, ..., 1/16 radian
constexpr int kRepeats = 4;  // steps per cap while the energy drops
// Centred caps: on the features and on a corner of each of the 32 sampled
// triangles that carry the most energy, radii 1, 1/2, ..., 1/256 radian.
constexpr int kHeavy = 32;
constexpr int kCentredLevels = 9;

// The i-th of n points spread evenly over the sphere (a Fibonacci lattice).
Vec3 fibonacci_point(int i, int n) {
  const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// From triangle `start`, walks across the edge of the most negative
// coordinate until a triangle's cone holds direction d; corners at
// position(u), `neighbours` as triangle_neighbours gives them. The triangle,
// or -1 after 64 steps or off the hemisphere.
template <class Position>
int walk(const std::vector<Triangle>& triangles, const std::vector<std::array<int, 3>>& neighbours, int start,
         const Vec3& d, const Position& position, double (&w)[3]) {
  constexpr int kSteps = 64;
  int f = start;
  for (int step = 0; step < kSteps && f >= 0; ++step) {
    const Triangle& t = triangles[f];
    const double lowest = radial_barycentric(d, position(t[0]), position(t[1]), position(t[2]), w);
    if (lowest >= -1e-12) return f;
    if (!std::isfinite(lowest)) return -1;
    // Edge k runs from corner k to k + 1: the one opposite corner j is j + 1.
    f = neighbours[f][(std::min_element(w, w + 3) - w + 1) % 3];
  }
  return -1;
}

}  // namespace

double MapOptimizer::region_move(Side& s, Side& o, const Vec3& c, double radius, bool scale_only) const {
  const Vec3 e1 = c.unitOrthogonal(), e2 = c.cross(e1);
  const double cos_radius = std::cos(radius);
  // The cap's movable vertices, their tangent coordinates at c and falloff.
  std::vector<int> members;
  std::vector<Eigen::Vector2d> tangent;
  std::vector<double> falloff;
  for (int v = 0; v < int(s.sphere.size()); ++v) {
    const Vec3& x = s.sphere[v];
    if (s.fixed[v] || x.dot(c) <= cos_radius) continue;
    const Vec3 off = x - x.dot(c) * c;
    const double sine = off.norm(), angle = std::atan2(sine, x.dot(c)), r = angle / radius;
    members.push_back(v);
    tangent.push_back(sine > 0 ? Eigen::Vector2d(Eigen::Vector2d(off.dot(e1), off.dot(e2)) * (angle / sine))
                               : Eigen::Vector2d::Zero());
    falloff.push_back((1 - r * r) * (1 - r * r));
  }
  if (members.empty()) return 0;
  const std::vector<int> faces = s.around(s.faces_of, members), sampled = s.around(s.sampled_of, members);
  // The other side's vertices inside the touched triangles, the triangle
  // holding each, and the sampled triangles around them.
  std::vector<int> held, held_faces;
  for (int f : faces)
    for (int w : s.holds[f]) held.push_back(w), held_faces.push_back(f);
  const std::vector<int> other_faces = o.around(o.sampled_of, held);
  // Each carried vertex's place in `members` or `held`, freed on every return.
  struct Slots {
    std::vector<int>& slot;
    const std::vector<int>& vertices;
    Slots(std::vector<int>& slot, const std::vector<int>& vertices) : slot(slot), vertices(vertices) {
      for (size_t i = 0; i < vertices.size(); ++i) slot[vertices[i]] = int(i);
    }
    ~Slots() {
      for (int v : vertices) slot[v] = -1;
    }
  } member_slots(s.slot, members), held_slots(o.slot, held);
  const double to_moving = std::sqrt(o.area / s.area);

  // The energy of the touched triangles after the deformation with
  // parameters q = (t, a) (+inf where a triangle thins too far); leaves the
  // members' new sphere points and images, and the held vertices' triangles
  // and images, in the vectors below.
  std::vector<Vec3> moved(members.size());
  std::vector<Image> member_images(members.size()), held_images(held.size());
  std::vector<int> new_held_faces(held.size());
  const auto position = [&](int v) -> const Vec3& {
    const int i = s.slot[v];
    return i >= 0 ? moved[i] : s.sphere[v];
  };
  const auto energy_at = [&](const Eigen::Vector3d& q) {
    for (size_t i = 0; i < members.size(); ++i) {
      const Eigen::Vector2d u = tangent[i] + falloff[i] * (q.z() * tangent[i] + radius * q.head<2>());
      const double angle = u.norm();
      moved[i] = angle > 0 ? Vec3(std::cos(angle) * c + std::sin(angle) / angle * (u.x() * e1 + u.y() * e2)) : c;
    }
    for (int f : faces) {
      const Triangle& t = s.surface.triangles[f];
      if (!(spherical_shape(position(t[0]), position(t[1]), position(t[2])) > s.min_shape[f])) return kInfinity;
    }
    for (size_t i = 0; i < members.size(); ++i) {
      const SphereLocation at = on_other_->locate(moved[i]);
      member_images[i] = o.image_in(at.triangle, at.barycentric.data(), 1 / to_moving);
    }
    for (size_t i = 0; i < held.size(); ++i) {
      const Vec3& d = o.sphere[held[i]];
      double w[3] = {1, 0, 0};
      int f = walk(s.surface.triangles, s.neighbours, held_faces[i], d, position, w);
      if (f < 0) f = s.holder(d, faces, position, w);
      if (f < 0) return kInfinity;
      new_held_faces[i] = f;
      held_images[i] = s.image_in(f, w, to_moving);
    }
    double energy = 0;
    for (int f : sampled)
      energy += s.triangle_energy(f, [&](int u) -> const Image& {
        const int i = s.slot[u];
        return i >= 0 ? member_images[i] : s.images[u];
      });
    for (int g : other_faces)
      energy += o.triangle_energy(g, [&](int u) -> const Image& {
        const int i = o.slot[u];
        return i >= 0 ? held_images[i] : o.images[u];
      });
    return energy;
  };

  const double e0 = energy_at(Eigen::Vector3d::Zero());
  if (!std::isfinite(e0)) return 0;
  constexpr double h = 1e-4;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  for (int k = scale_only ? 2 : 0; k < 3; ++k) {
    const Eigen::Vector3d d = h * Eigen::Vector3d::Unit(k);
    const double plus = energy_at(d), minus = energy_at(-d);
    if (!std::isfinite(plus) || !std::isfinite(minus)) return 0;
    gradient[k] = (plus - minus) / (2 * h);
  }
  if (!(gradient.norm() > 0)) return 0;
  const Eigen::Vector3d direction = -gradient.normalized();
  for (double step = 0.25; step > 1e-3; step *= 0.5) {
    const double energy = energy_at(step * direction);
    if (!(energy < e0)) continue;
    for (size_t i = 0; i < members.size(); ++i) {
      s.sphere[members[i]] = moved[i];
      s.images[members[i]] = member_images[i];
    }
    for (int f : faces) s.holds[f].clear();
    for (size_t i = 0; i < held.size(); ++i) {
      o.images[held[i]] = o.pending[held[i]] = held_images[i];
      s.holds[new_held_faces[i]].push_back(held[i]);
    }
    return e0 - energy;
  }
  return 0;
}

bool MapOptimizer::regions(Side& s, Side& o, const std::function<bool()>& keep_going) const {
  for (int level = 0; level < kLevels; ++level) {
    // 16 / R^2 centres: each point of the sphere lies in about 4 caps.
    const double radius = std::ldexp(1.0, -level);
    const int centres = int(std::ceil(16 / (radius * radius)));
    for (int i = 0; i < centres; ++i) {
      if (i % 256 == 0 && !keep_going()) return false;  // a fine level of a large mesh takes seconds
      const Vec3 centre = fibonacci_point(i, centres);
      for (int repeat = 0; repeat < kRepeats; ++repeat)
        if (!(region_move(s, o, centre, radius, false) > 0)) break;
    }
  }
  std::vector<std::pair<double, int>> heavy;  // (minus the energy, sampled triangle)
  for (int f = 0; f < int(s.sampled.size()); ++f)
    heavy.push_back({-s.triangle_energy(f, [&](int u) -> const Image& { return s.images[u]; }), f});
  const int count = std::min<int>(kHeavy, int(heavy.size()));
  std::partial_sort(heavy.begin(), heavy.begin() + count, heavy.end());
  std::vector<int> centred_on = s.centres;
  for (int i = 0; i < count; ++i) centred_on.push_back(s.sampled[heavy[i].second][0]);
  for (int level = 0; level < kCentredLevels; ++level) {
    const double radius = std::ldexp(1.0, -level);
    for (int v : centred_on) {
      if (!keep_going()) return false;
      for (int repeat = 0; repeat < kRepeats; ++repeat)
        if (!(region_move(s, o, s.sphere[v], radius, s.fixed[v]) > 0)) break;
    }
  }
  return true;
}

}  // namespace cmaps
