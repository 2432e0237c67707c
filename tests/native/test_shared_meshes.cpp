// Every mesh listed in shared/meshes/README.md reads with the listed vertex
// and face counts and checks with the listed genus, boundary loops, manifold
// flag and components; only the genus-0 closed manifold ones pass
// require_sphere_topology.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "consistent_maps/errors.h"
#include "consistent_maps/mesh_check.h"
#include "consistent_maps/mesh_io.h"
#include "test_support.h"

namespace cmaps {
namespace {

struct Row {
  std::string file;
  int vertices, faces;
  int genus;  // -1 for "n/a"
  int boundary_loops;
  bool manifold;
  int components;
};

void PrintTo(const Row& row, std::ostream* os) { *os << row.file; }

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(' '), end = s.find_last_not_of(' ');
  return begin == std::string::npos ? "" : s.substr(begin, end - begin + 1);
}

// Rows of the README table: "| file | V | F | genus | b | manifold | comps | ...".
std::vector<Row> readme_table() {
  std::ifstream in(test::shared_mesh("README.md"));
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| ", 0) != 0 || line.find("| file ") == 0) continue;
    std::vector<std::string> cells;
    std::stringstream cells_in(line.substr(1));
    for (std::string cell; std::getline(cells_in, cell, '|');) cells.push_back(trim(cell));
    if (cells.size() < 7 || cells[0].find('.') == std::string::npos) continue;
    rows.push_back({cells[0], std::stoi(cells[1]), std::stoi(cells[2]), cells[3] == "n/a" ? -1 : std::stoi(cells[3]),
                    std::stoi(cells[4]), cells[5] == "yes", std::stoi(cells[6])});
  }
  return rows;
}

class SharedMesh : public ::testing::TestWithParam<Row> {};

TEST_P(SharedMesh, MatchesReadme) {
  const Row& row = GetParam();
  const TriangleMesh mesh = read_mesh(test::shared_mesh(row.file));
  const MeshReport r = check_mesh(mesh);
  EXPECT_EQ(r.referenced_vertices, row.vertices);
  EXPECT_EQ(r.faces, row.faces);
  EXPECT_EQ(r.genus, row.genus);
  // Where boundary loops touch at non-manifold vertices, how they are split
  // into loops is a convention; the README's tool and check_mesh differ there.
  if (row.manifold) EXPECT_EQ(r.boundary_loops, row.boundary_loops);
  else EXPECT_EQ(r.boundary_loops > 0, row.boundary_loops > 0);
  EXPECT_EQ(r.manifold(), row.manifold);
  EXPECT_EQ(r.components, row.components);
  const bool sphere_like = row.genus == 0 && row.boundary_loops == 0 && row.manifold && row.components == 1;
  if (sphere_like && r.referenced_vertices == r.vertices) {
    EXPECT_NO_THROW(require_sphere_topology(mesh));
  } else if (!sphere_like) {
    EXPECT_THROW(require_sphere_topology(mesh), TopologyError);
  }
}

INSTANTIATE_TEST_SUITE_P(Readme, SharedMesh, ::testing::ValuesIn(readme_table()), [](const auto& test) {
  std::string name = test.param.file;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

TEST(SharedMeshes, TableIsComplete) { EXPECT_GE(readme_table().size(), 60u); }

}  // namespace
}  // namespace cmaps
