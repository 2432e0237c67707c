// A set of a mesh's edges by index, as flags: a path search asks at every
// step onto an edge's midpoint whether the edge is closed, and flags answer
// without a hash lookup.
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

#include "consistent_maps/errors.h"

namespace cmaps {

class EdgeSet {
 public:
  std::size_t count(int e) const { return e >= 0 && e < int(in_.size()) && in_[e]; }

  // Adds edge e (a valid index); the bool says whether it was not there yet.
  std::pair<int, bool> insert(int e) {
    if (e < 0) throw Error("internal error: a path edge that is no edge");
    if (e >= int(in_.size())) in_.resize(e + 1, 0);
    const bool added = !in_[e];
    in_[e] = 1;
    return {e, added};
  }

  void erase(int e) {
    if (count(e)) in_[e] = 0;
  }

 private:
  std::vector<char> in_;
};

}  // namespace cmaps
