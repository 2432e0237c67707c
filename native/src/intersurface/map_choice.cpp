#include "intersurface/map_choice.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/side_by_side.h"

namespace cmaps {

double summed_median(const IntersurfaceResult& r) {
  return r.distortion_a_to_b.median_symmetric_dirichlet + r.distortion_b_to_a.median_symmetric_dirichlet;
}

int summed_folds(const IntersurfaceResult& r) { return r.distortion_a_to_b.flipped + r.distortion_b_to_a.flipped; }

bool less_distorted(double mx, int fx, double my, int fy, std::size_t samples, bool x_wins_ties) {
  if (std::abs(mx - my) > 0.05 * std::min(mx, my)) return mx < my;
  if (std::abs(fx - fy) > 0.005 * double(samples)) return fx < fy;
  return x_wins_ties || mx < my;
}

bool less_distorted(const IntersurfaceResult& x, const IntersurfaceResult& y, std::size_t samples,
                    bool x_wins_ties) {
  return less_distorted(summed_median(x), summed_folds(x), summed_median(y), summed_folds(y), samples, x_wins_ties);
}

void add_stage_seconds(IntersurfaceResult& kept, const IntersurfaceResult& dropped) {
  kept.seconds_features += dropped.seconds_features;
  kept.seconds_partition += dropped.seconds_partition;
  kept.seconds_parameterize += dropped.seconds_parameterize;
  kept.seconds_optimize += dropped.seconds_optimize;
  kept.seconds_locate += dropped.seconds_locate;
  kept.seconds_measure += dropped.seconds_measure;
}

void exchange_sides(IntersurfaceResult& r) {
  std::swap(r.a_to_b, r.b_to_a);
  std::swap(r.a_corners_to_b, r.b_corners_to_a);
  std::swap(r.a_on_b, r.b_on_a);
  std::swap(r.distortion_a_to_b, r.distortion_b_to_a);
  std::swap(r.composition_a_to_b, r.composition_b_to_a);
  for (FeaturePair& f : r.features) std::swap(f.a, f.b);
  std::swap(r.efficiency_a, r.efficiency_b);
  std::swap(r.refitted_a, r.refitted_b);
  std::swap(r.steiner_a, r.steiner_b);
  std::swap(r.a_along_paths, r.b_along_paths);
  r.moved_b = !r.moved_b;
}

void keep_less_distorted(IntersurfaceResult& first, const std::exception_ptr& first_error,
                         IntersurfaceResult& second, const std::exception_ptr& second_error, std::size_t samples,
                         bool second_wins_ties) {
  const bool first_failed = failed_with_error(first_error), second_failed = failed_with_error(second_error);
  if (first_failed && second_failed) std::rethrow_exception(first_error);
  if (second_failed) return;
  if (first_failed) {
    first = std::move(second);
    return;
  }
  const bool second_wins = less_distorted(second, first, samples, second_wins_ties);
  add_stage_seconds(second_wins ? second : first, second_wins ? first : second);
  if (second_wins) first = std::move(second);
}

}  // namespace cmaps
