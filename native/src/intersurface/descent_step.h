// One step of the map optimizers' per-vertex descent (patch_map_optimization.h,
// cross_patch_optimization.h): a point of the canonical plane moves against
// the gradient of its energy (central differences, one-sided where a side is
// infinite: a turned or degenerate triangle) by half the mean length of its ring,
// halved up to ten times until the energy drops. The direction can come from
// another measure of the move (`key`) than the energy that decides.
#pragma once
#include <cmath>
#include <optional>
#include <utility>

#include "intersurface/patch_parameterization.h"

namespace cmaps {

// `trial(p)` returns a move with its `energy` (inf where p is not allowed);
// `current` is the move at x0. The first move found along -grad key(move)
// whose energy is lower, if any.
template <class Trial, class Key, class Move = decltype(std::declval<Trial>()(Vec2()))>
std::optional<Move> descent_step(const Vec2& x0, double length, const Move& current, const Trial& trial,
                                 const Key& key) {
  constexpr int kHalvings = 10;
  const double h = 1e-4 * length;
  const auto value = [&](const Move& move) { return std::isfinite(move.energy) ? key(move) : move.energy; };
  Vec2 gradient;
  for (int axis = 0; axis < 2; ++axis) {
    Vec2 d = Vec2::Zero();
    d[axis] = h;
    const double plus = value(trial(x0 + d)), minus = value(trial(x0 - d));
    if (std::isfinite(plus) && std::isfinite(minus)) gradient[axis] = (plus - minus) / (2 * h);
    else if (std::isfinite(plus)) gradient[axis] = (plus - key(current)) / h;
    else if (std::isfinite(minus)) gradient[axis] = (key(current) - minus) / h;
    else return std::nullopt;
  }
  if (!(gradient.norm() > 0)) return std::nullopt;
  const Vec2 direction = -gradient.normalized();
  double step = 0.5 * length;
  for (int k = 0; k < kHalvings; ++k, step *= 0.5) {
    Move move = trial(x0 + step * direction);
    if (move.energy < current.energy) return move;
  }
  return std::nullopt;
}

// Along the energy's own gradient.
template <class Trial, class Move = decltype(std::declval<Trial>()(Vec2()))>
std::optional<Move> descent_step(const Vec2& x0, double length, const Move& current, const Trial& trial) {
  return descent_step(x0, length, current, trial, [](const Move& m) { return m.energy; });
}

}  // namespace cmaps
