// Consistent partitioning on its own (issue 5: cow - horse in under 5 s;
// the thesis reports 98 s): the partition of A and B traced from the given
// feature pairs, then the paths moved to balance the patches' areas, each
// timed, best of three runs.
// Usage: partition_benchmark [A B FEATURES COLUMN_A COLUMN_B]
//   FEATURES: a JSON object {"name": [vertex or null per member], ...}
//   (bench/features/*.json); COLUMN_A, COLUMN_B: the members A and B are.
//   Default: genus0/cow.off and large/horse.ply with bench/features/animals.json.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "intersurface/consistent_partition.h"
#include "intersurface/patch_balance.h"
#include "json_reader.h"

using namespace cmaps;

static double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The pairs of a set's features file for its members `column_a` and `column_b` (features either lacks skipped).
static std::vector<std::array<int, 2>> feature_pairs(const std::string& path, int column_a, int column_b) {
  const JsonValue root = JsonParser::parse_file(path);
  const int members = root.members.empty() ? 0 : int(root.members.front().second.items.size());
  std::vector<std::array<int, 2>> pairs;
  for (const auto& [name, vertices] : read_set_feature_file(path, members))
    if (vertices.at(column_a) >= 0 && vertices.at(column_b) >= 0) pairs.push_back({vertices[column_a], vertices[column_b]});
  return pairs;
}

int main(int argc, char** argv) {
  const std::string meshes = CMAPS_SHARED_MESHES;
  const std::string path_a = argc > 5 ? argv[1] : meshes + "/genus0/cow.off";
  const std::string path_b = argc > 5 ? argv[2] : meshes + "/large/horse.ply";
  const std::string features = argc > 5 ? argv[3] : CMAPS_BENCH_FEATURES "/animals.json";
  const int column_a = argc > 5 ? std::atoi(argv[4]) : 1, column_b = argc > 5 ? std::atoi(argv[5]) : 0;
  TriangleMesh a = read_mesh(path_a), b = read_mesh(path_b);
  const int genus = check_mesh(a).genus;
  // Oriented alike, as intersurface_map lays them.
  if (signed_volume(a) * signed_volume(b) < 0)
    for (Triangle& t : b.triangles) std::swap(t[1], t[2]);
  for (const auto& [name, first, second, pairs] :
       {std::tuple{"A -> B", &a, &b, feature_pairs(features, column_a, column_b)},
        std::tuple{"B -> A", &b, &a, feature_pairs(features, column_b, column_a)}}) {
    double trace = 1e30, balance = 1e30;
    ConsistentPartition kept;
    for (int run = 0; run < 3; ++run) {
      auto start = std::chrono::steady_clock::now();
      ConsistentPartition partition = consistent_partition(*first, *second, pairs, genus);
      trace = std::min(trace, seconds_since(start));
      start = std::chrono::steady_clock::now();
      balance_patch_areas(partition, 4);
      balance = std::min(balance, seconds_since(start));
      kept = std::move(partition);
    }
    std::printf("%s: %zu pairs, %zu base triangles, Steiner %d / %d; partition %.2f s, balancing %.2f s\n", name,
                pairs.size(), kept.triangles.size(),
                kept.sides[0].mesh.vertex_count() - kept.sides[0].mesh.input_vertex_count(),
                kept.sides[1].mesh.vertex_count() - kept.sides[1].mesh.input_vertex_count(), trace, balance);
  }
  return 0;
}
