#pragma once
/// @file block_matrix.hpp
/// @brief A sparse matrix of dense 3x3 node blocks (BSR) for the per-step
/// products with A and K: one column index per block instead of nine, and a
/// fixed-size 3x3 kernel, so an SpMV streams about 2/3 of the CSR bytes.
///
/// Contract: built from a row-major CSR whose pattern consists of full 3x3
/// blocks in node order (what assemble() produces); values are copied, so
/// later changes of the CSR matrix are not seen.

#include "membrane/assembly.hpp"

#include <Eigen/Dense>

#include <vector>

namespace lamina::membrane {

/// 3x3-block compressed sparse rows.
class BlockMatrix {
public:
  BlockMatrix() = default;
  /// Copies @p A (3n x 3n, full 3x3 blocks).
  explicit BlockMatrix(const SparseMatrix& A);
  /// y = A x (OpenMP over block rows for large matrices).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// @return the diagonal 3x3 block of node @p i
  Eigen::Matrix3d diagonalBlock(int i) const;
  /// @return number of node rows
  int nodes() const { return static_cast<int>(start_.size()) - 1; }

private:
  std::vector<int> start_;  // block row pointers
  std::vector<int> col_;    // block column (node) of each block
  std::vector<double> val_; // 9 values per block, row-major
};

} // namespace lamina::membrane
