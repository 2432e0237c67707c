// Exact nearest-point queries over a fixed point set (PathGuide's iterative
// closest points match a few thousand points per round, many rounds).
#pragma once
#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include "consistent_maps/mesh.h"

namespace cmaps {

// Exact nearest-point queries over a fixed set: a k-d tree (median splits
// along the box's widest axis), the query's side searched first and the other
// only while the splitting plane lies no farther than the nearest point found.
// Ties go to the lowest index, as a scan in order would give them.
class NearestPoint {
 public:
  explicit NearestPoint(const std::vector<Vec3>& points) : points_(points), order_(points.size()) {
    std::iota(order_.begin(), order_.end(), 0);
    if (!order_.empty()) build(0, int(order_.size()));
  }

  int operator()(const Vec3& p) const {
    int best = 0;
    double d = std::numeric_limits<double>::infinity();
    if (!nodes_.empty()) search(0, p, best, d);
    return best;
  }

 private:
  static constexpr int kLeaf = 8;  // points a leaf holds at most
  struct Node {
    int begin, end;  // its points: order_[begin, end)
    int axis = -1;   // -1 for a leaf
    double split = 0;
    int below = -1, above = -1;  // children: coordinates <= split, >= split
  };

  int build(int begin, int end) {
    const int id = int(nodes_.size());
    nodes_.push_back({begin, end});
    if (end - begin <= kLeaf) return id;
    Eigen::AlignedBox3d box;
    for (int k = begin; k < end; ++k) box.extend(points_[order_[k]]);
    int axis = 0;
    box.sizes().maxCoeff(&axis);
    const int middle = (begin + end) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                     [&](int i, int j) { return points_[i][axis] < points_[j][axis]; });
    const double split = points_[order_[middle]][axis];
    const int below = build(begin, middle), above = build(middle, end);
    nodes_[id].axis = axis, nodes_[id].split = split, nodes_[id].below = below, nodes_[id].above = above;
    return id;
  }

  void search(int id, const Vec3& p, int& best, double& d) const {
    const Node& node = nodes_[id];
    if (node.axis < 0) {
      for (int k = node.begin; k < node.end; ++k) {
        const int i = order_[k];
        const double di = (points_[i] - p).squaredNorm();
        if (di < d || (di == d && i < best)) d = di, best = i;
      }
      return;
    }
    const double offset = p[node.axis] - node.split;
    search(offset < 0 ? node.below : node.above, p, best, d);
    if (offset * offset <= d) search(offset < 0 ? node.above : node.below, p, best, d);
  }

  const std::vector<Vec3>& points_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace cmaps
