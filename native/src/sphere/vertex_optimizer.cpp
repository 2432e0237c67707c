#include "sphere/vertex_optimizer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/coloured_sweeps.h"

namespace cmaps {

VertexOptimizer::VertexOptimizer(const MeshRefinement& mesh, const std::vector<FaceWeights>& weights,
                                 std::vector<Vec3>& sphere, int threads)
    : mesh_(mesh), weights_(weights), sphere_(sphere), threads_(std::max(1, threads)) {}

double VertexOptimizer::star_energy(int v, const Vec3& p, Vec3* gradient) const {
  if (gradient) gradient->setZero();
  double energy = 0;
  const auto& triangles = mesh_.triangles();
  for (int f : mesh_.faces_of(v)) {
    const Triangle& t = triangles[f];
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const FaceWeights& w = weights_[f];
    energy += corner_energy(p, sphere_[t[k1]], sphere_[t[k2]], {w[k], w[k1], w[k2]}, gradient);
    if (!std::isfinite(energy)) return energy;
  }
  if (term_) {
    energy += term_->star_energy(mesh_, v, p, sphere_);
    if (gradient) *gradient += correspondence_gradient(v, p);
  }
  return energy;
}

Vec3 VertexOptimizer::correspondence_gradient(int v, const Vec3& p) const {
  double shortest = std::numeric_limits<double>::infinity();
  for (int f : mesh_.faces_of(v))
    for (int u : mesh_.triangles()[f])
      if (u != v) shortest = std::min(shortest, (sphere_[u] - p).norm());
  const double h = 1e-4 * shortest;
  const Vec3 t[2] = {p.unitOrthogonal(), p.cross(p.unitOrthogonal())};
  Vec3 g = Vec3::Zero();
  for (const Vec3& d : t) {
    const double up = term_->star_energy(mesh_, v, (p + h * d).normalized(), sphere_);
    const double down = term_->star_energy(mesh_, v, (p - h * d).normalized(), sphere_);
    g += (up - down) / (2 * h) * d;
  }
  return g;
}

double VertexOptimizer::total_energy() const {
  double energy = 0;
  const auto& triangles = mesh_.triangles();
  for (size_t f = 0; f < triangles.size(); ++f)
    if (mesh_.face_active(f)) {
      const Triangle& t = triangles[f];
      energy += corner_energy(sphere_[t[0]], sphere_[t[1]], sphere_[t[2]], weights_[f], nullptr);
    }
  return energy;
}

// One-dimensional Newton steps along the vertex's great-circle arc, between
// its current chain neighbours, with the same kernel rule (energy +inf
// outside the kernel rejects a step).
double VertexOptimizer::optimize_on_arc(int v, int iterations) {
  const auto [lo, hi] = arcs_->neighbours(mesh_, v);
  Vec3 origin, axis;
  arcs_->frame(sphere_, arcs_->chain_of[v], origin, axis);
  auto angle = [&](const Vec3& p) { return std::atan2(p.dot(axis), p.dot(origin)); };
  auto point = [&](double t) -> Vec3 { return std::cos(t) * origin + std::sin(t) * axis; };
  const double t_lo = angle(sphere_[lo]), t_hi = angle(sphere_[hi]);
  double t = angle(sphere_[v]);
  const Vec3 start = sphere_[v];
  if (!(t_hi > t_lo) || !(t > t_lo && t < t_hi)) return 0;
  const double room = std::min(t - t_lo, t_hi - t);
  auto derivative = [&](double s, double* energy) {
    Vec3 g = Vec3::Zero();
    *energy = star_energy(v, point(s), &g);
    return g.dot(-std::sin(s) * origin + std::cos(s) * axis);
  };
  for (int it = 0; it < iterations; ++it) {
    double e0;
    const double d = derivative(t, &e0);
    if (!std::isfinite(e0) || d == 0) break;
    const double h = 1e-3 * std::min(t - t_lo, t_hi - t);
    double eh;
    const double dh = derivative(t + (d > 0 ? -h : h), &eh);
    const double second = (dh - d) / (d > 0 ? -h : h);
    double step = std::isfinite(eh) && second > 0 ? -d / second : -(d > 0 ? 1 : -1) * 0.25 * (t_hi - t_lo);
    // Stay strictly between the neighbours.
    if (t + step >= t_hi) step = 0.5 * (t_hi - t);
    if (t + step <= t_lo) step = 0.5 * (t_lo - t);
    bool accepted = false;
    for (double f = 1; std::abs(f * step) > 1e-3 * h; f *= 0.5) {
      const double e = star_energy(v, point(t + f * step), nullptr);
      if (e <= e0 + 1e-4 * f * step * d) {
        t += f * step;
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
  }
  sphere_[v] = point(t);
  if (term_) term_->moved(v, sphere_[v]);
  return (sphere_[v] - start).norm() / std::max(1e-300, std::sin(room));
}

double VertexOptimizer::optimize_vertex(int v, int iterations) {
  if (!fixed_.empty() && fixed_[v]) return 0;
  if (arcs_ && arcs_->constrained(v)) return optimize_on_arc(v, iterations);
  const Vec3 start = sphere_[v];
  Vec3 p = start;
  // The longest chord to a neighbour caps the step. The clearance, the
  // distance to the nearest great circle bounding the kernel, sets the
  // finite-difference step and how far the line search may shrink: any move
  // shorter than it is valid.
  double reach = 0, clearance = std::numeric_limits<double>::infinity();
  const auto& triangles = mesh_.triangles();
  for (int f : mesh_.faces_of(v)) {
    const Triangle& t = triangles[f];
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const Vec3 &a = sphere_[t[(k + 1) % 3]], &b = sphere_[t[(k + 2) % 3]];
    reach = std::max(reach, (a - p).norm());
    const Vec3 normal = a.cross(b);
    clearance = std::min(clearance, p.dot(normal) / normal.norm());
  }
  if (!(clearance > 0) || !std::isfinite(reach)) return 0;
  const double scale = std::min(reach, clearance);
  for (int it = 0; it < iterations; ++it) {
    const Vec3 t1 = p.unitOrthogonal(), t2 = p.cross(t1);
    // Gradient of u -> E(normalize(p + u1 t1 + u2 t2)) at u.
    auto tangent_gradient = [&](const Eigen::Vector2d& u, double* energy) -> Eigen::Vector2d {
      const Vec3 raw = p + u.x() * t1 + u.y() * t2;
      const double len = raw.norm();
      const Vec3 q = raw / len;
      Vec3 g;
      *energy = star_energy(v, q, &g);
      const Vec3 gt = (g - q * q.dot(g)) / len;
      return {gt.dot(t1), gt.dot(t2)};
    };
    double e0;
    const Eigen::Vector2d g = tangent_gradient({0, 0}, &e0);
    if (!std::isfinite(e0) || g.norm() == 0) break;
    const double h = 1e-3 * scale;
    Eigen::Matrix2d hessian;
    bool newton = true;
    for (int i = 0; i < 2 && newton; ++i) {
      double ei;
      const Eigen::Vector2d gi = tangent_gradient(Eigen::Vector2d::Unit(i) * h, &ei);
      newton = std::isfinite(ei);
      hessian.col(i) = (gi - g) / h;
    }
    Eigen::Vector2d step;
    if (newton) {
      hessian = 0.5 * (hessian + hessian.transpose()).eval();
      if (hessian.determinant() > 0 && hessian.trace() > 0)
        step = -hessian.inverse() * g;
      else
        newton = false;
    }
    if (!newton) step = -g * (0.25 * reach / g.norm());
    if (step.norm() > reach) step *= reach / step.norm();

    const double slope = g.dot(step);
    bool accepted = false;
    for (double t = 1; t * step.norm() > 1e-3 * scale; t *= 0.5) {
      const Vec3 q = (p + t * step.x() * t1 + t * step.y() * t2).normalized();
      const double e = star_energy(v, q, nullptr);
      if (e <= e0 + 1e-4 * t * slope) {
        p = q;
        accepted = true;
        break;
      }
    }
    if (!accepted || step.norm() < 1e-9 * scale) {
      if (accepted) sphere_[v] = p;
      break;
    }
    sphere_[v] = p;
  }
  sphere_[v] = p;
  if (term_) term_->moved(v, p);
  return (p - start).norm() / scale;
}

void VertexOptimizer::optimize_all(int max_sweeps, double tolerance) {
  if (term_) term_->refresh_all(sphere_, threads_);
  const VertexColouring colouring = colour_vertices(
      static_cast<int>(sphere_.size()), mesh_.triangles(), [&](size_t f) { return mesh_.face_active(f); },
      [&](int v) { return mesh_.vertex_active(v); });
  coloured_sweeps(
      colouring, threads_, max_sweeps, tolerance, [&](int v) { return optimize_vertex(v, 1); },
      [](int) { return true; }, [](const std::vector<int>&) {});
}

}  // namespace cmaps
