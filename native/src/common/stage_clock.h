// Stage bookkeeping: the clock a stage's seconds are read from, and a
// stage's slice of the caller's progress.
#pragma once
#include <chrono>
#include <string>

#include "consistent_maps/progress.h"

namespace cmaps {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline ProgressCallback slice(const ProgressCallback& progress, double begin, double end) {
  if (!progress) return {};
  return [&progress, begin, end](double f, const std::string& stage) {
    return progress(begin + (end - begin) * f, stage);
  };
}

}  // namespace cmaps
