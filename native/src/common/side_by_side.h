// Independent computations run side by side, on new threads and the
// caller's, reporting progress as one: on a two-core machine a pair of
// mostly serial stages finishes in the time of the longer one, and a queue
// of them keeps both cores busy until the last.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "consistent_maps/progress.h"

namespace cmaps {

// The caller's progress fed by several computations: the weighted sum of
// their fractions, reported under the lock (the callback need not be
// thread-safe). Once any is told to stop, all are.
class JointProgress {
 public:
  JointProgress(const ProgressCallback& progress, std::vector<double> weights)
      : progress_(progress), weight_(std::move(weights)), fraction_(weight_.size(), 0) {}

  ProgressCallback part(int k) {
    return [this, k](double fraction, const std::string& stage) {
      std::lock_guard<std::mutex> lock(mutex_);
      fraction_[k] = fraction;
      double sum = 0;
      for (std::size_t i = 0; i < weight_.size(); ++i) sum += weight_[i] * fraction_[i];
      if (!stopped_ && progress_ && !progress_(sum, stage)) stopped_ = true;
      return !stopped_;
    };
  }

  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }

  bool stopped() {
    std::lock_guard<std::mutex> lock(mutex_);
    return stopped_;
  }

 private:
  const ProgressCallback& progress_;
  const std::vector<double> weight_;
  std::vector<double> fraction_;
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

// Runs task(k, progress) for every k in [0, weights.size()) on `workers`
// threads (a new one each but one, and the caller's), the tasks taken in
// order of k as threads come free, each reporting its progress as
// weights[k] of the whole; then finished(k, thrown), under one lock, as each
// ends. Returns what each task threw (null when it returned): a task that
// throws a cancellation or a failure other than a cmaps::Error stops the
// others early (those not yet started throw Cancelled at once), and so does
// `finished` throwing anything (kept as its task's).
template <class Task, class Finished>
std::vector<std::exception_ptr> run_tasks(const ProgressCallback& progress, std::vector<double> weights, int workers,
                                          Task&& task, Finished&& finished) {
  const int count = int(weights.size());
  JointProgress joint(progress, std::move(weights));
  std::vector<std::exception_ptr> thrown(count);
  std::atomic<int> next{0};
  std::mutex finishing;
  const auto run = [&] {
    for (int k; (k = next++) < count;) {
      try {
        if (joint.stopped()) throw Cancelled();
        task(k, joint.part(k));
      } catch (const Cancelled&) {
        thrown[k] = std::current_exception();
        joint.stop();
      } catch (const Error&) {
        thrown[k] = std::current_exception();
      } catch (...) {
        thrown[k] = std::current_exception();
        joint.stop();
      }
      std::lock_guard<std::mutex> lock(finishing);
      try {
        finished(k, thrown[k]);
      } catch (...) {
        thrown[k] = std::current_exception();
        joint.stop();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(workers, count); ++t) pool.emplace_back(run);
  run();
  for (std::thread& t : pool) t.join();
  return thrown;
}

// Runs first(progress) and second(progress) side by side, one on a new
// thread and one on the caller's, both to the end (see run_tasks), and
// returns what each threw.
template <class First, class Second>
std::array<std::exception_ptr, 2> run_side_by_side(const ProgressCallback& progress, double first_weight,
                                                   First&& first, Second&& second) {
  const std::vector<std::exception_ptr> thrown = run_tasks(
      progress, {first_weight, 1 - first_weight}, 2,
      [&](int k, const ProgressCallback& part) { k == 0 ? first(part) : second(part); },
      [](int, const std::exception_ptr&) {});
  return {thrown[0], thrown[1]};
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
