// Fill and factorization time of the sparse LU behind the patch embeddings
// and the balancing's harmonic functions (common/diagonally_dominant_lu.h)
// against Eigen's default, COLAMD ordering with partial pivoting. The system:
// a disk of the mesh's vertices grown breadth-first from vertex 0, each at a
// mean of its neighbours with random positive weights (unequal both ways
// along an edge, as stretch reweighting makes them), the disk's rim fixed.
// Usage: lu_ordering_benchmark [MESH [UNKNOWNS...]]
//   Default: large/horse.ply with 1,000 to 48,000 unknowns.
#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "common/diagonally_dominant_lu.h"
#include "consistent_maps/mesh_io.h"

using namespace cmaps;

struct Disk {
  Eigen::SparseMatrix<double> matrix;
  Eigen::MatrixXd rhs;
};

static Disk disk(const TriangleMesh& mesh, int unknowns) {
  std::vector<std::vector<int>> neighbours(mesh.vertices.size());
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) neighbours[t[k]].push_back(t[(k + 1) % 3]);
  std::vector<int> unknown(mesh.vertices.size(), -1), grown{0};
  unknown[0] = 0;
  for (std::size_t h = 0; h < grown.size() && int(grown.size()) < unknowns; ++h)
    for (int w : neighbours[grown[h]])
      if (unknown[w] < 0 && int(grown.size()) < unknowns) unknown[w] = int(grown.size()), grown.push_back(w);
  const int n = int(grown.size());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> weight(0.1, 10);
  std::vector<Eigen::Triplet<double>> entries;
  Disk system{Eigen::SparseMatrix<double>(n, n), Eigen::MatrixXd::Zero(n, 2)};
  for (int i = 0; i < n; ++i)
    for (int w : neighbours[grown[i]]) {
      const double x = weight(random);
      entries.emplace_back(i, i, x);
      if (unknown[w] >= 0) entries.emplace_back(i, unknown[w], -x);
      else system.rhs.row(i) += x * Eigen::RowVector2d(mesh.vertices[w].x(), mesh.vertices[w].y());
    }
  system.matrix.setFromTriplets(entries.begin(), entries.end());
  return system;
}

// Nonzeros of L and U, and the best of three factorizations in milliseconds.
template <class Solver>
static void measure(const char* name, Solver& lu, const Disk& system) {
  lu.analyzePattern(system.matrix);
  double best = 1e300;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    lu.factorize(system.matrix);
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  const Eigen::MatrixXd x = lu.solve(system.rhs);
  std::printf("  %-8s %10ld nonzeros %9.1f ms  residual %.1e\n", name, long(lu.nnzL() + lu.nnzU()), best,
              (system.matrix * x - system.rhs).cwiseAbs().maxCoeff());
}

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(CMAPS_SHARED_MESHES) + "/large/horse.ply";
  std::vector<int> sizes;
  for (int k = 2; k < argc; ++k) sizes.push_back(std::stoi(argv[k]));
  if (sizes.empty()) sizes = {1000, 4000, 16000, 30000, 48000};
  const TriangleMesh mesh = read_mesh(path);
  for (int n : sizes) {
    const Disk system = disk(mesh, n);
    std::printf("%s, %d unknowns, %ld entries\n", path.c_str(), int(system.matrix.rows()),
                long(system.matrix.nonZeros()));
    Eigen::SparseLU<Eigen::SparseMatrix<double>> colamd;
    measure("COLAMD", colamd, system);
    DiagonallyDominantLU amd;
    measure("AMD", amd, system);
  }
}
