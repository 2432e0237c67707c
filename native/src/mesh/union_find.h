// Disjoint sets with path halving and union by size: near-linear connectivity
// queries for components, fans and boundary loops.
#pragma once
#include <numeric>
#include <utility>
#include <vector>

namespace cmaps {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }

  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }

  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<int> parent_, size_;
};

}  // namespace cmaps
