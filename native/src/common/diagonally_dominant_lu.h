// Sparse LU for the mesh systems of the pipeline: a row per interior vertex,
// its diagonal at least the sum of its row's other weights (convex-combination
// embeddings, harmonic functions), the pattern symmetric (the mesh's edges).
//
// Such a matrix wants a symmetric fill-reducing ordering with the diagonal as
// pivot. Eigen's default, COLAMD, orders columns for any row pivoting and
// fills more: a disk of 16,000 of the horse's vertices factors into 1.48 M
// nonzeros (72 ms) against AMD's 0.92 M (47 ms; bench/lu_ordering_benchmark).
// Eigen's AMDOrdering cannot be plugged into SparseLU as it is: it returns
// the permutation from new positions to old columns, SparseLU reads the one
// from old columns to new positions, and the inverse of a good ordering fills
// like a bad one (12.7 M nonzeros against COLAMD's 0.44 M in this solver's test).
#pragma once
#include <Eigen/OrderingMethods>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

namespace cmaps {

// AMD on the pattern of A + A^T, as SparseLU's column permutation.
struct AmdColumnOrdering {
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

  template <class Matrix>
  void operator()(const Matrix& matrix, PermutationType& permutation) const {
    PermutationType new_to_old;
    Eigen::AMDOrdering<int>()(matrix, new_to_old);
    permutation = new_to_old.inverse();
  }
};

class DiagonallyDominantLU : public Eigen::SparseLU<Eigen::SparseMatrix<double>, AmdColumnOrdering> {
 public:
  // The diagonal is the pivot unless an entry below it is ten times larger:
  // the ordering's fill stays, and elimination on a diagonally dominant
  // matrix is stable without pivoting anyway.
  DiagonallyDominantLU() { setPivotThreshold(0.1); }
};

}  // namespace cmaps
