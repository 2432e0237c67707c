// Computations side by side (common/side_by_side.h): two run to the end and
// report one monotone progress; a failure of one leaves the other's result; a
// cancellation, from the caller or from either side, stops both. A queue of
// them starts its tasks in order and stops at a failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <mutex>
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

// A queue of tasks: each runs once, `finished` sees each end, and progress
// is one monotone sum; on one thread they run in order (on three, a task's
// record of its start can lag behind the next one's, so only the set is
// checked).
TEST(SideBySide, TasksQueueInOrder) {
  for (const int workers : {1, 3}) {
    std::vector<double> seen;
    const ProgressCallback progress = [&](double f, const std::string&) {
      seen.push_back(f);
      return true;
    };
    std::mutex lock;
    std::vector<int> started, ended;
    std::array<std::atomic<int>, 7> steps{};
    const auto thrown = run_tasks(
        progress, std::vector<double>(7, 1.0 / 7), workers,
        [&](int k, const ProgressCallback& p) {
          {
            std::lock_guard<std::mutex> hold(lock);
            started.push_back(k);
          }
          std::atomic<int> done{0};
          count(p, 10 + 5 * k, &done);
          steps[k] = done.load();
        },
        [&](int k, const std::exception_ptr& e) {
          EXPECT_FALSE(e);
          ended.push_back(k);  // under run_tasks' lock
        });
    const std::vector<int> all{0, 1, 2, 3, 4, 5, 6};
    if (workers == 1) EXPECT_EQ(started, all);
    std::sort(started.begin(), started.end());
    std::sort(ended.begin(), ended.end());
    EXPECT_EQ(started, all) << workers << " threads";
    EXPECT_EQ(ended, all) << workers << " threads";
    for (int k = 0; k < 7; ++k) {
      EXPECT_FALSE(thrown[k]);
      EXPECT_EQ(steps[k], 10 + 5 * k);
    }
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
    EXPECT_NEAR(seen.back(), 1.0, 1e-12);
  }
}

// A failure other than a cmaps::Error, in a task or in `finished`, stops the
// queue: the tasks not started throw Cancelled without running; an Error
// stops nothing.
TEST(SideBySide, AFailureStopsTheQueue) {
  for (const bool in_finished : {false, true}) {
    std::array<std::atomic<bool>, 6> ran{};
    const auto thrown = run_tasks(
        {}, std::vector<double>(6, 1.0 / 6), 2,
        [&](int k, const ProgressCallback& p) {
          ran[k] = true;
          if (k == 0) throw InvalidInput("stuck");
          count(p, k == 2 ? 100000 : 5);
          if (k == 1 && !in_finished) throw std::bad_alloc();
        },
        [&](int k, const std::exception_ptr&) {
          if (k == 1 && in_finished) throw std::bad_alloc();
        });
    EXPECT_TRUE(failed_with_error(thrown[0]));
    EXPECT_THROW(failed_with_error(thrown[1]), std::bad_alloc);
    // Task 2 is stopped while it runs, or skipped if it had not started.
    EXPECT_THROW(failed_with_error(thrown[2]), Cancelled);
    for (int k = 3; k < 6; ++k) {
      EXPECT_THROW(failed_with_error(thrown[k]), Cancelled);
      EXPECT_FALSE(ran[k]) << "task " << k;
    }
  }
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
