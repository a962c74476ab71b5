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
/// (unstructured meshes) the plain block storage is used: blocks stored
/// column-major, and on CPUs with AVX a block's three rows are computed in
/// one 4-wide register (a column of the block times one component of x).
/// AVX without FMA and the same order of operations per component as the
/// row-major scalar product (y_c += A(c,0) x_0 + A(c,1) x_1 + A(c,2) x_2,
/// block after block in column order): the same bits with or without AVX.
///
/// Split blocks: when no block couples the in-plane components (0, 1) with
/// the normal one (2) (every A(0,2), A(1,2), A(2,0), A(2,1) exactly zero:
/// the flat membrane of a law without in-plane/transverse-shear coupling,
/// e.g. any isotropic, orthotropic or monoclinic-about-z material), the
/// plain storage keeps five numbers per block, the 2x2 in-plane block and
/// A(2,2): 44 bytes per block with its column index instead of 76, for a
/// product that is bound by streaming the matrix. The products are those of
/// the 3x3 blocks without the terms that are exact zeros (x + 0 = x for a
/// finite x): the same numbers, up to the sign of a zero (with an infinite
/// or NaN w the 3x3 kernel's 0 * w would have spread a NaN to u and v).
/// Split blocks are stored in slices of four consecutive rows, block k of
/// each row side by side (a row shorter than its slice's longest ends in
/// zero blocks on its own column, 1 % more blocks on a gmsh square), so that
/// the four rows of a slice are the four lanes of one AVX2 register, x
/// gathered: each row's sum keeps its order, so the same bits as row by row
/// (for a finite x: a padding block adds 0 x_i, which turns an infinite x_i
/// into NaN in row i, non-finite either way), without the branch that ends
/// each row of a few blocks. A(2,2) is stored apart from the in-plane
/// values, so that a product of the normal component alone streams it and
/// the columns only: 12 of the 44 bytes per block.
///
/// Normal plane alone: with split blocks of finite entries, a vector whose
/// in-plane components are all exactly zero has a product whose in-plane
/// components are +0 (each row's sum starts at +0 and adds only zeros) and whose
/// normal component is A(2,2) x_2. The transverse motion of the linear
/// membrane under transverse load (a strike, a pressure) is such a vector
/// at every step. multiply() and multiplyDot() find it (one pass over x)
/// and compute the normal plane alone; the CG asks for it with
/// BlockPlanes::Normal. The results are the bits of the full product.
///
/// Two vector layouts. Interleaved (the solver's): dof 3 i + c. Planar (the
/// CG iteration's): component c of node i at c n + i, three contiguous
/// planes. With shared rows, consecutive nodes of one stored row (a "run",
/// e.g. the interior of a grid line) then apply the same nine numbers per
/// block to consecutive entries of each plane: a loop the compiler
/// vectorizes (core/parallel.hpp compiles it for AVX-512, AVX2 and SSE2).
/// The interleaved product of a shared-row matrix goes through the planar
/// kernel (two extra passes to transpose, still several times faster).
///
/// Contract: built from a row-major CSR whose pattern consists of full 3x3
/// blocks in node order (what assemble() produces); values are copied, so
/// later changes of the CSR matrix are not seen. multiply() and
/// multiplyDot() use scratch of the object: do not call them on one object
/// from two threads at once.

#include "membrane/model/assembly.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace lamina::membrane {

/// Copies nodes [@p i0, @p i1) of the interleaved vector @p a (dof 3 i + c)
/// into the planar vector @p p (c n + i), @p n nodes in all.
void toPlanar(const double* a, double* p, int n, int i0, int i1);
/// Copies nodes [@p i0, @p i1) of the planar @p p into the interleaved @p a.
void fromPlanar(const double* p, double* a, int n, int i0, int i1);

/// How a BlockMatrix stores its blocks.
enum class BlockStorage {
  Automatic, ///< shared rows on a repeated stencil, else split blocks when
             ///< they decouple, else plain 3x3 blocks (the solvers' choice)
  Plain      ///< plain 3x3 blocks always (the benchmarks' floor, tests)
};

/// Which code computes the plain-block product (unstructured meshes).
enum class BlockKernel {
  Fastest, ///< AVX for 3x3 blocks and AVX2 for split blocks when the CPU has
           ///< them, else Scalar (the default)
  Scalar   ///< the portable loop a CPU without AVX (3x3) or AVX2 (split) runs
           ///< (same bits)
};

/// Which planes of a planar product are computed.
enum class BlockPlanes {
  All,   ///< the three components
  Normal ///< component 2 alone (split blocks; the caller guarantees that
         ///< components 0 and 1 of x are zero and holds +0 in those of y)
};

/// Whether products may compute the normal plane alone when the in-plane
/// components are zero (a switch for the tests that compare the two).
enum class PlaneSkipping {
  Automatic, ///< when the blocks are split and x's in-plane part is zero (the default)
  Never      ///< always the three components
};

/// @return true when components 0 and 1 of nodes [@p i0, @p i1) of @p v are
/// exactly zero (either sign; NaN is not), component c of node i at s i + c o.
bool inPlaneZero(const double* v, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1);

/// 3x3-block compressed sparse rows.
class BlockMatrix {
public:
  /// Chooses the plain-block kernel of every BlockMatrix of the process
  /// (tests compare the two on a CPU that has AVX and AVX2; not thread-safe
  /// against products running at the same time).
  static void useKernel(BlockKernel kernel);
  /// Chooses whether products of every BlockMatrix of the process may skip
  /// zero in-plane components (same thread-safety as useKernel()).
  static void usePlaneSkipping(PlaneSkipping skipping);
  /// @return true when products may compute the normal plane alone
  static bool skipsZeroPlanes();
  BlockMatrix() = default;
  /// Copies @p A (3n x 3n, full 3x3 blocks) in the storage @p storage.
  explicit BlockMatrix(const SparseMatrix& A, BlockStorage storage = BlockStorage::Automatic);
  /// y = A x, interleaved vectors (OpenMP over block rows for large matrices).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// y = A x and @return x.y, in one pass (interleaved vectors).
  double multiplyDot(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// Planar y = A x on the node rows [@p begin, @p end) (x whole, y written
  /// only on those rows; no threads: the caller splits the rows).
  /// BlockPlanes::Normal (split blocks only) computes and writes component 2
  /// alone: the caller guarantees that components 0 and 1 of x are zero
  /// (then those of A x are +0, which y must already hold).
  /// @return the part of x.y from those rows.
  double multiplyPlanar(const double* x, double* y, int begin, int end,
                        BlockPlanes planes = BlockPlanes::All) const;
  /// @return the diagonal 3x3 block of node @p i
  Eigen::Matrix3d diagonalBlock(int i) const;
  /// @return number of node rows
  int nodes() const { return n_; }
  /// @return the stored row of node @p i when rows are shared (else @p i)
  int rowOf(int i) const { return kind_.empty() ? i : kind_[i]; }
  /// @return number of distinct stored rows (0 = no row sharing)
  int sharedRows() const { return kind_.empty() ? 0 : static_cast<int>(kstart_.size()) - 1; }
  /// @return number of stored rows (distinct rows, or one per node)
  int storedRows() const { return kind_.empty() ? n_ : sharedRows(); }
  /// @return true when the blocks are stored split (in-plane 2x2 and normal)
  bool splitBlocks() const { return split_; }

  /// Calls @p f(b, e, row) for the runs [b, e) of consecutive nodes in
  /// [@p begin, @p end) that share stored row @p row (one node per call
  /// without row sharing), in node order.
  template <class F>
  void forEachRun(int begin, int end, F&& f) const {
    if (kind_.empty()) {
      for (int i = begin; i < end; ++i)
        f(i, i + 1, i);
      return;
    }
    // run_begin_ is sorted; the run holding node `begin` is the last one starting at or before it.
    auto k = std::upper_bound(run_begin_.begin(), run_begin_.end(), begin) - run_begin_.begin() - 1;
    for (int b = begin; b < end; ++k) {
      const int e = std::min(end, run_begin_[k + 1]);
      f(b, e, kind_[b]);
      b = e;
    }
  }

private:
  void shareRepeatedRows();
  /// Plain storage: split blocks when @p may_split and every block
  /// decouples, else column-major 3x3 blocks.
  void storePlainBlocks(bool may_split);
  /// Split blocks in slices of consecutive rows (the lanes of the product):
  /// replaces start_, col_ and val_ (row-major 3x3 blocks) by the slices,
  /// A(2,2) in val22_.
  void storeSlices();
  /// y = A x on the rows [@p begin, @p end) of plain storage, component c
  /// of node j at s j + c o in x and y; @return x.y there (3x3 blocks on
  /// AVX and split blocks on AVX2 when the CPU has them; the same bits as
  /// the scalar loops either way).
  double plainRows(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o, int begin,
                   int end) const;
  /// The normal component of plainRows() for split blocks and an x whose
  /// in-plane components are zero; with @p store_zeros the +0 in-plane
  /// components of y are stored too (interleaved vectors).
  double normalRows(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o, int begin,
                    int end, bool store_zeros) const;
  template <bool Dot>
  double product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  template <bool Dot>
  double productViaPlanar(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  int n_ = 0;
  std::vector<int> kind_;               // per node: its stored row (empty = plain storage)
  std::vector<int> kstart_;             // per stored row: first entry
  std::vector<int> koff_;               // per entry: column node minus row node
  std::vector<double> kval_;            // per entry: 9 values, row-major
  std::vector<int> run_begin_;          // first node of each run of equal kind_, then n
  std::vector<int> start_;              // block row pointers; split: first slot per slice
  std::vector<int> col_;                // block column (node) of each block; split: per
                                        // slot, one per lane
  std::vector<double> val_;             // 9 values per block, column-major, then one pad;
                                        // split: per slot a00, a10, a01, a11, each one
                                        // per lane
  std::vector<double> val22_;           // split: per slot a22, one per lane
  bool split_ = false;                  // plain storage in split blocks
  mutable std::vector<double> xs_, ys_; // planar scratch of multiply() (shared rows)
};

} // namespace lamina::membrane
