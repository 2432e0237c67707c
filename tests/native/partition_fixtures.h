// Partitioned pairs the patch-wise map's tests start from.
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "consistent_maps/mesh_io.h"
#include "intersurface/consistent_partition.h"
#include "intersurface/patch_map_optimization.h"
#include "intersurface/patch_parameterization.h"
#include "test_support.h"

namespace cmaps::test {

// Per vertex of a side: whether it lies on one of the partition's paths.
inline std::vector<char> on_paths(const PartitionSide& side) {
  std::vector<char> on_path(side.mesh.vertex_count(), 0);
  for (const auto& path : side.paths)
    for (int v : path) on_path[v] = 1;
  return on_path;
}

// Two poses of one cactus (vertex i onto vertex i), partitioned between
// farthest-point pairs (8 unless said).
struct CactusPoses {
  explicit CactusPoses(int count = 8) : count(count) {}
  const int count;
  const TriangleMesh a = read_mesh(shared_mesh("sets/cactus/cactus0.ply"));
  const TriangleMesh b = read_mesh(shared_mesh("sets/cactus/cactus1.ply"));
  const std::vector<std::array<int, 2>> pairs = [this] {
    std::vector<std::array<int, 2>> pairs;
    for (int v : farthest_points(a, count)) pairs.push_back({v, v});
    return pairs;
  }();
  ConsistentPartition p = consistent_partition(a, b, pairs, 0);
};

// Eight -> skull from the pair `cmaps intersurface eight.off skull.obj
// --starts 1` starts from, its patch map optimized with the paths as walls:
// what the optimization across paths starts from.
struct EightSkull {
  const TriangleMesh a = read_mesh(shared_mesh("higher-genus/eight.off"));
  const TriangleMesh b = read_mesh(shared_mesh("higher-genus/skull.obj"));
  ConsistentPartition p = consistent_partition(a, b, {{317, 4614}}, 2);
  PatchParameterization uv_a = parameterize_patches(p.sides[0], p);
  const PatchParameterization uv_b = parameterize_patches(p.sides[1], p);
  const MapOptimization walls = optimize_patch_map(p.sides[0], uv_a, p.sides[1], uv_b, 20, 2);
  const double scale = std::sqrt(side_area(p.sides[0]) / side_area(p.sides[1]));
};

}  // namespace cmaps::test
