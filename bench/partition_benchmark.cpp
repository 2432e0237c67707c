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
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "intersurface/consistent_partition.h"
#include "intersurface/patch_balance.h"

using namespace cmaps;

static double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The pairs of a features file's two columns (rows with null in either are skipped).
static std::vector<std::array<int, 2>> feature_pairs(const std::string& path, int column_a, int column_b) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string json = text.str();
  std::vector<std::array<int, 2>> pairs;
  const std::regex row("\"[^\"]*\"\\s*:\\s*\\[([^\\]]*)\\]");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), row); it != std::sregex_iterator(); ++it) {
    std::vector<std::string> cells;
    std::stringstream list((*it)[1].str());
    for (std::string cell; std::getline(list, cell, ',');)
      cells.push_back(cell.substr(cell.find_first_not_of(" \n\t")));
    const std::string &a = cells.at(column_a), &b = cells.at(column_b);
    if (a.rfind("null", 0) == 0 || b.rfind("null", 0) == 0) continue;
    pairs.push_back({std::stoi(a), std::stoi(b)});
  }
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
