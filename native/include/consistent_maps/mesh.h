// The library's plain mesh: a vertex array and a triangle array. Algorithms
// build their own adjacency from it; this type carries no invariants beyond
// "triangle indices refer to vertices" once validated.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products everywhere
#include <array>
#include <vector>

namespace cmaps {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<int, 3>;

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

}  // namespace cmaps
