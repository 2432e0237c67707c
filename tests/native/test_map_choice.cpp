// Which of two inter-surface maps is kept (intersurface/map_choice.h): the
// rule every route uses (sphere restarts, screened starts, both sides, the
// sphere's map against the direct one), on hand-made results.
#include <gtest/gtest.h>

#include <exception>

#include "consistent_maps/errors.h"
#include "intersurface/map_choice.h"

namespace cmaps {
namespace {

// A result with the given medians and folds per direction and 1 s per stage.
IntersurfaceResult made(double median_ab, double median_ba, int folds_ab, int folds_ba) {
  IntersurfaceResult r;
  r.distortion_a_to_b.median_symmetric_dirichlet = median_ab;
  r.distortion_b_to_a.median_symmetric_dirichlet = median_ba;
  r.distortion_a_to_b.flipped = folds_ab;
  r.distortion_b_to_a.flipped = folds_ba;
  r.seconds_features = r.seconds_partition = r.seconds_parameterize = 1;
  r.seconds_optimize = r.seconds_locate = r.seconds_measure = 1;
  return r;
}

std::exception_ptr failure(const char* what) { return std::make_exception_ptr(Error(what)); }

TEST(MapChoice, LowerSummedMedianWinsBeyondFivePercent) {
  const IntersurfaceResult x = made(5, 5, 900, 900), y = made(5.3, 5.3, 0, 0);  // 10 against 10.6: 6 % apart
  EXPECT_DOUBLE_EQ(summed_median(x), 10);
  EXPECT_EQ(summed_folds(x), 1800);
  EXPECT_TRUE(less_distorted(x, y, 1000));  // folds do not count past the 5 %
  EXPECT_FALSE(less_distorted(y, x, 1000));
}

TEST(MapChoice, WithinFivePercentClearlyFewerFoldsWin) {
  // Medians 10 and 10.4 tie; 1,000 samples: folds must differ by more than 5.
  EXPECT_FALSE(less_distorted(10, 100, 10.4, 0, 1000));
  EXPECT_TRUE(less_distorted(10.4, 0, 10, 100, 1000));
  EXPECT_TRUE(less_distorted(10.4, 0, 10, 6, 1000));
  // Folds 5 apart are noise: the lower median, or x when ties go to it.
  EXPECT_FALSE(less_distorted(10.4, 0, 10, 5, 1000));
  EXPECT_TRUE(less_distorted(10.4, 0, 10, 5, 1000, /*x_wins_ties=*/true));
  EXPECT_TRUE(less_distorted(10, 5, 10.4, 0, 1000));
}

TEST(MapChoice, ExchangingSidesTwiceGivesTheMapBack) {
  IntersurfaceResult r = made(4, 6, 1, 2);
  r.features = {{3, 7}};
  r.a_to_b = {{0, {1, 0, 0}}};
  r.steiner_a = 10, r.steiner_b = 20;
  exchange_sides(r);
  EXPECT_DOUBLE_EQ(r.distortion_a_to_b.median_symmetric_dirichlet, 6);
  EXPECT_EQ(r.features[0].a, 7);
  EXPECT_EQ(r.features[0].b, 3);
  EXPECT_TRUE(r.a_to_b.empty());
  EXPECT_EQ(r.b_to_a.size(), 1u);
  EXPECT_EQ(r.steiner_a, 20);
  exchange_sides(r);
  EXPECT_DOUBLE_EQ(r.distortion_a_to_b.median_symmetric_dirichlet, 4);
  EXPECT_EQ(r.features[0].a, 3);
  EXPECT_EQ(r.a_to_b.size(), 1u);
  EXPECT_EQ(r.steiner_b, 20);
}

TEST(MapChoice, KeepsTheLessDistortedAndCountsBothTimes) {
  IntersurfaceResult first = made(6, 6, 0, 0), second = made(5, 5, 0, 0);
  keep_less_distorted(first, nullptr, second, nullptr, 1000);
  EXPECT_DOUBLE_EQ(summed_median(first), 10);
  EXPECT_DOUBLE_EQ(first.seconds_optimize, 2);  // the dropped map's time added
  // A tie goes to the second map only when asked.
  IntersurfaceResult a = made(5, 5, 0, 0), b = made(5.1, 5.1, 0, 0);
  keep_less_distorted(a, nullptr, b, nullptr, 1000, /*second_wins_ties=*/true);
  EXPECT_DOUBLE_EQ(summed_median(a), 10.2);
}

TEST(MapChoice, AFailedMapLeavesTheOtherAndACancellationPropagates) {
  IntersurfaceResult first = made(6, 6, 0, 0), second = made(50, 50, 0, 0);
  keep_less_distorted(first, failure("stuck"), second, nullptr, 1000);
  EXPECT_DOUBLE_EQ(summed_median(first), 100);
  IntersurfaceResult kept = made(6, 6, 0, 0), failed = made(5, 5, 0, 0);
  keep_less_distorted(kept, nullptr, failed, failure("stuck"), 1000);
  EXPECT_DOUBLE_EQ(summed_median(kept), 12);
  IntersurfaceResult x = made(6, 6, 0, 0), y = made(5, 5, 0, 0);
  try {
    keep_less_distorted(x, failure("first"), y, failure("second"), 1000);
    ADD_FAILURE() << "both maps failed, yet one was kept";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "first");
  }
  EXPECT_THROW(keep_less_distorted(x, std::make_exception_ptr(Cancelled()), y, nullptr, 1000), Cancelled);
}

}  // namespace
}  // namespace cmaps
