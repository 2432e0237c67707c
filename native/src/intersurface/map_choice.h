// Which of two inter-surface maps of a pair to keep (sphere restarts, direct
// maps from several starts or from both sides, the sphere's map against the
// direct one), and the bookkeeping of the map dropped.
#pragma once
#include <cstddef>
#include <exception>

#include "consistent_maps/intersurface_map.h"

namespace cmaps {

// A -> B plus B -> A median distortion.
double summed_median(const IntersurfaceResult& r);

// A -> B plus B -> A folded samples.
int summed_folds(const IntersurfaceResult& r);

// Whether map x of a pair is better than map y: the lower summed median,
// unless the medians lie within 5 % of each other. Such medians are a tie
// the energy cannot break (restarts of one sphere map differ by 1-2 %; the
// truth of sets/faces is more distorted than both maps): the map that folds
// fewer sampled triangles (both directions) by more than 0.5 % of the
// `samples` (A's triangles plus B's) wins, folds showing as inverted faces
// in a morph; with fold counts closer than that, x when `x_wins_ties`, else
// still the lower median. Fold counts a few apart are noise (on sets/faces
// and the torus against its stretched copy they picked the farther map as
// often as not); hundreds apart they are not: sets/cactus 2 -> 0, 12
// features, 0 folds and 0.7 % off the truth against 207 folds and 1.5 %.
bool less_distorted(double mx, int fx, double my, int fy, std::size_t samples, bool x_wins_ties = false);
bool less_distorted(const IntersurfaceResult& x, const IntersurfaceResult& y, std::size_t samples,
                    bool x_wins_ties = false);

// The stage times of a map computed and dropped, added to the one kept.
void add_stage_seconds(IntersurfaceResult& kept, const IntersurfaceResult& dropped);

// The same map seen from the other side: A and B exchanged.
void exchange_sides(IntersurfaceResult& r);

// Of two maps computed side by side, the one to keep, left in `first`: a
// cancellation is rethrown, a map whose computation failed leaves the other
// (both failed: first's error rethrown), else the less distorted wins (a
// tie goes to `second` when `second_wins_ties`), the other's stage times added.
void keep_less_distorted(IntersurfaceResult& first, const std::exception_ptr& first_error,
                         IntersurfaceResult& second, const std::exception_ptr& second_error, std::size_t samples,
                         bool second_wins_ties = false);

}  // namespace cmaps
