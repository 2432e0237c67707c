// Two independent computations run side by side, one on a new thread and one
// on the caller's, reporting progress as one: on a two-core machine a pair of
// mostly serial stages finishes in the time of the longer one.
#pragma once
#include <algorithm>
#include <array>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

#include "consistent_maps/progress.h"

namespace cmaps {

// The caller's progress fed by two computations: the weighted sum of their
// fractions, reported under the lock (the callback need not be thread-safe).
// Once either is told to stop, both are.
class JointProgress {
 public:
  JointProgress(const ProgressCallback& progress, double first_weight)
      : progress_(progress), weight_{first_weight, 1 - first_weight} {}

  ProgressCallback part(int k) {
    return [this, k](double fraction, const std::string& stage) {
      std::lock_guard<std::mutex> lock(mutex_);
      fraction_[k] = fraction;
      if (!stopped_ && progress_ && !progress_(weight_[0] * fraction_[0] + weight_[1] * fraction_[1], stage))
        stopped_ = true;
      return !stopped_;
    };
  }

  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }

 private:
  const ProgressCallback& progress_;
  const double weight_[2];
  double fraction_[2] = {0, 0};
  bool stopped_ = false;
  std::mutex mutex_;
};

// The worker threads `threads` allows, shared by two computations run side
// by side: the first gets the larger half, each at least one. Each passing
// the whole count on to its own parallel loops only oversubscribed the
// cores (cow - horse unfeatured, `--method auto`, the direct map's two
// sides halved: 89 -> 86 s, peak memory 835 -> 723 MB).
inline std::array<int, 2> split_threads(int threads) {
  return {std::max(1, (threads + 1) / 2), std::max(1, threads / 2)};
}

// Runs first(progress) on a new thread and second(progress) on this one,
// both to the end, and returns what each threw (null when it returned). A
// cancellation or a failure other than a cmaps::Error stops the other early.
template <class First, class Second>
std::array<std::exception_ptr, 2> run_side_by_side(const ProgressCallback& progress, double first_weight,
                                                   First&& first, Second&& second) {
  JointProgress joint(progress, first_weight);
  std::array<std::exception_ptr, 2> thrown;
  const auto guarded = [&](int k, auto& compute) {
    try {
      compute(joint.part(k));
    } catch (const Cancelled&) {
      thrown[k] = std::current_exception();
      joint.stop();
    } catch (const Error&) {
      thrown[k] = std::current_exception();
    } catch (...) {
      thrown[k] = std::current_exception();
      joint.stop();
    }
  };
  std::thread worker([&] { guarded(0, first); });
  guarded(1, second);
  worker.join();
  return thrown;
}

// True when `thrown` holds a cmaps::Error other than a cancellation, a
// failure the caller can fall back from; rethrows anything else.
inline bool failed_with_error(const std::exception_ptr& thrown) {
  if (!thrown) return false;
  try {
    std::rethrow_exception(thrown);
  } catch (const Cancelled&) {
    throw;
  } catch (const Error&) {
    return true;
  }
}

}  // namespace cmaps
