// One step of the map optimizers' per-vertex descent: a point of the
// canonical plane moves against a gradient (map_gradient.h: of its energy,
// or of another measure of the move) from half the mean length of its ring
// (patch_map_optimization.h), or takes the Newton step of its energy, the
// Hessian by differences of the gradient (cross_patch_optimization.h, where
// the map is refined last); halved until the energy drops.
#pragma once
#include <Eigen/Dense>
#include <optional>
#include <utility>

#include "intersurface/patch_parameterization.h"

namespace cmaps {

// A step along a gradient has no length of its own: it is halved up to ten
// times. A Newton step has one: one that fails four halvings sits at a kink
// of the piecewise linear map, where shorter ones rarely help (kitten - elk:
// the same map quality, two fifths of the failed trials); the step that unfolds
// a ring before the energy's own gets as few.
constexpr int kGuessedHalvings = 10;
constexpr int kScaledHalvings = 4;

// `trial(p)` returns a move with its `energy` (inf where p is not allowed);
// `current` is the move at x0. The first of x0 + step, x0 + step / 2, ...
// (`halvings` trials) whose energy is lower, if any.
template <class Trial, class Move = decltype(std::declval<Trial>()(Vec2()))>
std::optional<Move> line_search(const Vec2& x0, Vec2 step, int halvings, const Move& current, const Trial& trial) {
  for (int k = 0; k < halvings; ++k, step *= 0.5) {
    Move move = trial(x0 + step);
    if (move.energy < current.energy) return move;
  }
  return std::nullopt;
}

// Along -gradient, from half the ring's mean length `length`.
template <class Trial, class Move = decltype(std::declval<Trial>()(Vec2()))>
std::optional<Move> descent_step(const Vec2& x0, const Vec2& gradient, double length, int halvings,
                                 const Move& current, const Trial& trial) {
  if (!(gradient.norm() > 0)) return std::nullopt;
  return line_search(x0, Vec2(-0.5 * length * gradient.normalized()), halvings, current, trial);
}

// The Newton step of the energy, whose gradient at x0 is `gradient` and at
// p is gradient_at(p) (nothing where p is not allowed).
template <class Trial, class GradientAt, class Move = decltype(std::declval<Trial>()(Vec2()))>
std::optional<Move> newton_step(const Vec2& x0, const Vec2& gradient, double length, const Move& current,
                                const Trial& trial, const GradientAt& gradient_at) {
  if (!(gradient.norm() > 0)) return std::nullopt;
  const double h = 1e-3 * length;
  const std::optional<Vec2> along_x = gradient_at(x0 + Vec2(h, 0)), along_y = gradient_at(x0 + Vec2(0, h));
  if (along_x && along_y) {
    Eigen::Matrix2d hessian;
    hessian << (*along_x - gradient) / h, (*along_y - gradient) / h;
    hessian = 0.5 * (hessian + hessian.transpose()).eval();
    if (hessian.determinant() > 0 && hessian.trace() > 0) {
      Vec2 step = -hessian.inverse() * gradient;
      if (step.norm() > 0.5 * length) step *= 0.5 * length / step.norm();
      return line_search(x0, step, kScaledHalvings, current, trial);
    }
  }
  return descent_step(x0, gradient, length, kGuessedHalvings, current, trial);
}

}  // namespace cmaps
