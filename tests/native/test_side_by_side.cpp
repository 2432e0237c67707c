// Two computations side by side (common/side_by_side.h): both run to the end
// and report one monotone progress; a failure of one leaves the other's
// result; a cancellation, from the caller or from either side, stops both.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "common/side_by_side.h"

namespace cmaps {
namespace {

// Reports `steps` fractions, throwing Cancelled when told to stop.
void count(const ProgressCallback& progress, int steps, std::atomic<int>* done = nullptr) {
  for (int i = 1; i <= steps; ++i) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    if (!progress(double(i) / steps, "counting")) throw Cancelled();
    if (done) ++*done;
  }
}

TEST(SideBySide, BothRunAndProgressIsOneMonotoneSum) {
  std::vector<double> seen;
  const ProgressCallback progress = [&](double f, const std::string&) {
    seen.push_back(f);  // called under the joint lock
    return true;
  };
  std::atomic<int> first{0}, second{0};
  const auto thrown = run_side_by_side(
      progress, 0.25, [&](const ProgressCallback& p) { count(p, 50, &first); },
      [&](const ProgressCallback& p) { count(p, 80, &second); });
  EXPECT_FALSE(thrown[0]);
  EXPECT_FALSE(thrown[1]);
  EXPECT_EQ(first, 50);
  EXPECT_EQ(second, 80);
  ASSERT_EQ(seen.size(), 130u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
}

TEST(SideBySide, AnErrorOfOneLeavesTheOther) {
  std::atomic<int> second{0};
  const auto thrown = run_side_by_side(
      {}, 0.5, [](const ProgressCallback&) { throw InvalidInput("stuck"); },
      [&](const ProgressCallback& p) { count(p, 40, &second); });
  EXPECT_TRUE(failed_with_error(thrown[0]));
  EXPECT_FALSE(failed_with_error(thrown[1]));
  EXPECT_EQ(second, 40);
}

TEST(SideBySide, CancellingStopsBoth) {
  int calls = 0;
  const ProgressCallback progress = [&](double, const std::string&) { return ++calls < 10; };
  std::atomic<int> first{0}, second{0};
  const auto thrown = run_side_by_side(
      progress, 0.5, [&](const ProgressCallback& p) { count(p, 1000, &first); },
      [&](const ProgressCallback& p) { count(p, 1000, &second); });
  EXPECT_THROW(failed_with_error(thrown[0]), Cancelled);
  EXPECT_THROW(failed_with_error(thrown[1]), Cancelled);
  EXPECT_LT(first + second, 20);
}

// Any failure other than a cmaps::Error stops the other side too, and is
// rethrown rather than fallen back from.
TEST(SideBySide, AnUnexpectedFailureStopsTheOther) {
  std::atomic<int> second{0};
  const auto thrown = run_side_by_side(
      {}, 0.5, [](const ProgressCallback&) { throw std::bad_alloc(); },
      [&](const ProgressCallback& p) { count(p, 100000, &second); });
  EXPECT_THROW(failed_with_error(thrown[0]), std::bad_alloc);
  EXPECT_THROW(failed_with_error(thrown[1]), Cancelled);
  EXPECT_LT(second, 100000);
}

// Two computations side by side share the caller's worker threads rather
// than each taking all of them; each keeps at least its own.
TEST(SideBySide, ThreadsAreSharedBetweenBothSides) {
  using Split = std::array<int, 2>;
  EXPECT_EQ(split_threads(1), (Split{1, 1}));
  EXPECT_EQ(split_threads(2), (Split{1, 1}));
  EXPECT_EQ(split_threads(3), (Split{2, 1}));
  EXPECT_EQ(split_threads(16), (Split{8, 8}));
}

}  // namespace
}  // namespace cmaps
