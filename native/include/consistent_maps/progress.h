// Progress reporting and cooperative cancellation for long computations.
#pragma once
#include <functional>
#include <string>

#include "consistent_maps/errors.h"

namespace cmaps {

// Called with a fraction in [0, 1] and the current stage name. Returning
// false asks the computation to stop; it then throws cmaps::Cancelled.
using ProgressCallback = std::function<bool(double fraction, const std::string& stage)>;

// Maps a stage's local progress [0, 1] into a slice [begin, end] of the
// overall progress and forwards it, throwing Cancelled when asked to stop.
class ProgressSlice {
 public:
  ProgressSlice(const ProgressCallback& callback, std::string stage, double begin, double end)
      : callback_(callback), stage_(std::move(stage)), begin_(begin), end_(end) {}

  void report(double local_fraction) const {
    if (callback_ && !callback_(begin_ + (end_ - begin_) * local_fraction, stage_)) throw Cancelled();
  }

 private:
  const ProgressCallback& callback_;
  std::string stage_;
  double begin_, end_;
};

}  // namespace cmaps
