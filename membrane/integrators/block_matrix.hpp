#pragma once
/// @file block_matrix.hpp
/// @brief A sparse matrix of dense 3x3 node blocks (BSR) for the per-step
/// products with A and K: one column index per block instead of nine, and a
/// fixed-size 3x3 kernel, so an SpMV streams about 2/3 of the CSR bytes.
///
/// Repeated rows: on a uniform structured mesh most block rows are the same
/// stencil (same column offsets j - i, same blocks). When the distinct rows
/// are fewer than 1/16 of the nodes, rows equal to within 1e-14 of their
/// largest entry (a few ulps of assembly round-off) share one stored copy and
/// the product streams only x, y and one row index per node. Otherwise
/// (unstructured meshes) the plain block storage is used.
///
/// Contract: built from a row-major CSR whose pattern consists of full 3x3
/// blocks in node order (what assemble() produces); values are copied, so
/// later changes of the CSR matrix are not seen.

#include "membrane/model/assembly.hpp"

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
  /// y = A x and @return x.y, in one pass.
  double multiplyDot(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// @return the diagonal 3x3 block of node @p i
  Eigen::Matrix3d diagonalBlock(int i) const;
  /// @return number of node rows
  int nodes() const { return n_; }
  /// @return the stored row of node @p i when rows are shared (else @p i)
  int rowOf(int i) const { return kind_.empty() ? i : kind_[i]; }
  /// @return number of distinct stored rows (0 = no row sharing)
  int sharedRows() const { return kind_.empty() ? 0 : static_cast<int>(kstart_.size()) - 1; }

private:
  void shareRepeatedRows();
  template <bool Dot>
  double product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  int n_ = 0;
  std::vector<int> kind_;    // per node: its stored row (empty = plain storage)
  std::vector<int> kstart_;  // per stored row: first entry
  std::vector<int> koff_;    // per entry: column node minus row node
  std::vector<double> kval_; // per entry: 9 values, row-major
  std::vector<int> start_;   // block row pointers
  std::vector<int> col_;     // block column (node) of each block
  std::vector<double> val_;  // 9 values per block, row-major
};

} // namespace lamina::membrane
