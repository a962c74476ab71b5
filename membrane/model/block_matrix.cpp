#include "membrane/model/block_matrix.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace lamina::membrane {

BlockMatrix::BlockMatrix(const SparseMatrix& A, BlockStorage storage) {
  LAMINA_CHECK(A.rows() % 3 == 0 && A.rows() == A.cols(), "BlockMatrix needs a 3n x 3n matrix");
  const int n = static_cast<int>(A.rows() / 3);
  n_ = n;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* v = A.valuePtr();
  start_.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    const int len = outer[3 * i + 1] - outer[3 * i];
    LAMINA_CHECK(len % 3 == 0 && outer[3 * i + 2] - outer[3 * i + 1] == len &&
                     outer[3 * i + 3] - outer[3 * i + 2] == len,
                 "BlockMatrix: row ", 3 * i, " is not made of 3x3 blocks");
    start_[i + 1] = start_[i] + len / 3;
  }
  col_.resize(start_[n]);
  val_.resize(9 * static_cast<size_t>(start_[n]));
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < start_[i + 1] - start_[i]; ++k) {
      const int b = start_[i] + k;
      col_[b] = inner[outer[3 * i] + 3 * k] / 3;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          val_[9 * b + 3 * c + d] = v[outer[3 * i + c] + 3 * k + d];
    }
  if (storage == BlockStorage::Automatic) {
    shareRepeatedRows();
    if (!kind_.empty())
      return;
  }
  storePlainBlocks(storage == BlockStorage::Automatic);
}

void BlockMatrix::storePlainBlocks(bool may_split) {
  const std::size_t nb = col_.size();
  // Row-major values: (0,2) at 2, (1,2) at 5, (2,0) at 6, (2,1) at 7.
  split_ = may_split && nb > 0;
  for (std::size_t b = 0; b < nb && split_; ++b) {
    const double* m = val_.data() + 9 * b;
    split_ = m[2] == 0 && m[5] == 0 && m[6] == 0 && m[7] == 0;
  }
  if (split_) {
    std::vector<double> v(5 * nb);
    for (std::size_t b = 0; b < nb; ++b) {
      const double* m = val_.data() + 9 * b;
      double* w = v.data() + 5 * b;
      w[0] = m[0]; // the 2x2 block column-major, then A(2,2)
      w[1] = m[3];
      w[2] = m[1];
      w[3] = m[4];
      w[4] = m[8];
    }
    val_ = std::move(v);
    return;
  }
  // Column-major 3x3 blocks (plainRows() loads a column at once), one pad
  // value so the last column's 4-wide load stays inside.
  for (std::size_t b = 0; b < nb; ++b) {
    double* m = val_.data() + 9 * b;
    std::swap(m[1], m[3]);
    std::swap(m[2], m[6]);
    std::swap(m[5], m[7]);
  }
  val_.push_back(0.0);
}

void BlockMatrix::shareRepeatedRows() {
  const int n = n_;
  if (n < 64)
    return;
  const int limit = n / 16;
  std::unordered_map<std::string, int> seen;
  std::vector<int> kind(n), first;
  std::string key;
  auto sameRow = [&](int i, int r, double quantum) {
    if (start_[i + 1] - start_[i] != start_[r + 1] - start_[r])
      return false;
    for (int b = start_[i], c = start_[r]; b < start_[i + 1]; ++b, ++c) {
      if (col_[b] - i != col_[c] - r)
        return false;
      for (int q = 0; q < 9; ++q)
        if (std::abs(val_[9 * b + q] - val_[9 * c + q]) > quantum)
          return false;
    }
    return true;
  };
  for (int i = 0; i < n; ++i) {
    double scale = 0;
    for (int b = start_[i]; b < start_[i + 1]; ++b)
      for (int q = 0; q < 9; ++q)
        scale = std::max(scale, std::abs(val_[9 * b + q]));
    const double quantum = scale > 0 ? 1e-14 * scale : 1.0;
    // The previous node's row first: equal within the quantum, the two nodes
    // join one run even where round-off puts them on either side of a level.
    if (i > 0 && sameRow(i, first[kind[i - 1]], quantum)) {
      kind[i] = kind[i - 1];
      continue;
    }
    key.clear();
    for (int b = start_[i]; b < start_[i + 1]; ++b) {
      const std::int32_t off = col_[b] - i;
      key.append(reinterpret_cast<const char*>(&off), sizeof off);
      for (int q = 0; q < 9; ++q) {
        const auto level = static_cast<std::int64_t>(std::llround(val_[9 * b + q] / quantum));
        key.append(reinterpret_cast<const char*>(&level), sizeof level);
      }
    }
    const auto it = seen.emplace(key, static_cast<int>(first.size()));
    if (it.second) {
      first.push_back(i);
      if (static_cast<int>(first.size()) > limit)
        return; // not a repeated stencil: keep the plain block storage
    }
    kind[i] = it.first->second;
  }
  kstart_.assign(1, 0);
  for (int r : first) {
    for (int b = start_[r]; b < start_[r + 1]; ++b) {
      koff_.push_back(col_[b] - r);
      kval_.insert(kval_.end(), val_.begin() + 9 * b, val_.begin() + 9 * b + 9);
    }
    kstart_.push_back(static_cast<int>(koff_.size()));
  }
  kind_ = std::move(kind);
  run_begin_.clear();
  for (int i = 0; i < n; ++i)
    if (i == 0 || kind_[i] != kind_[i - 1])
      run_begin_.push_back(i);
  run_begin_.push_back(n);
  std::vector<int>().swap(col_);
  std::vector<double>().swap(val_);
  std::vector<int>().swap(start_);
}

namespace {

/// Planar y = A x on the nodes [i0, i1) of one run: every node applies the
/// blocks m[9 b..] at column offsets off[b], b in [0, nb). @return x.y there.
LAMINA_VECTOR_CLONES
double runProduct(const int* off, const double* m, int nb, int n, const double* __restrict x,
                  double* __restrict y, int i0, int i1) {
  const double* __restrict x0 = x;
  const double* __restrict x1 = x + n;
  const double* __restrict x2 = x + 2 * static_cast<std::ptrdiff_t>(n);
  double* __restrict y0 = y;
  double* __restrict y1 = y + n;
  double* __restrict y2 = y + 2 * static_cast<std::ptrdiff_t>(n);
  for (int i = i0; i < i1; ++i)
    y0[i] = y1[i] = y2[i] = 0;
  for (int b = 0; b < nb; ++b, m += 9) {
    const std::ptrdiff_t o = off[b];
    const double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3], m4 = m[4], m5 = m[5], m6 = m[6],
                 m7 = m[7], m8 = m[8];
    for (int i = i0; i < i1; ++i) {
      const double a = x0[i + o], c = x1[i + o], d = x2[i + o];
      y0[i] += m0 * a + m1 * c + m2 * d;
      y1[i] += m3 * a + m4 * c + m5 * d;
      y2[i] += m6 * a + m7 * c + m8 * d;
    }
  }
  double dot = 0;
#pragma omp simd reduction(+ : dot)
  for (int i = i0; i < i1; ++i)
    dot += x0[i] * y0[i] + x1[i] * y1[i] + x2[i] * y2[i];
  return dot;
}

/// Stores row @p i's result (@p y0, @p y1, @p y2) in @p y (component c of
/// node i at s i + c o) and @return its part of x.y.
inline double storeRow(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i,
                       double y0, double y1, double y2) {
  double* yi = y + s * i;
  const double* xi = x + s * i;
  yi[0] = y0;
  yi[o] = y1;
  yi[2 * o] = y2;
  return xi[0] * y0 + xi[o] * y1 + xi[2 * o] * y2;
}

/// Plain blocks (column-major: m[3 d + c] = A(c, d)) on the rows [i0, i1):
/// component c of node j of x and y at s j + c o (interleaved: s = 3, o = 1;
/// planar: s = 1, o = n). Per row the operations and their order of the
/// row-major product y_c += A(c,0) x_0 + A(c,1) x_1 + A(c,2) x_2, block
/// after block. @return x.y on those rows, summed in node order.
double plainRowsScalar(const int* start, const int* col, const double* val, const double* x,
                       double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  for (int i = i0; i < i1; ++i) {
    double y0 = 0, y1 = 0, y2 = 0;
    for (int b = start[i]; b < start[i + 1]; ++b) {
      const double* m = val + 9 * static_cast<std::size_t>(b);
      const double* xj = x + s * col[b];
      const double a = xj[0], c = xj[o], d = xj[2 * o];
      y0 += m[0] * a + m[3] * c + m[6] * d;
      y1 += m[1] * a + m[4] * c + m[7] * d;
      y2 += m[2] * a + m[5] * c + m[8] * d;
    }
    dot += storeRow(x, y, s, o, i, y0, y1, y2);
  }
  return dot;
}

/// plainRowsScalar() for split blocks (m = a00 a10 a01 a11 a22 per block):
/// the same products and sums without the terms that are exact zeros, so the
/// same numbers as the 3x3 blocks (up to the sign of a zero).
double splitRows(const int* start, const int* col, const double* val, const double* x, double* y,
                 std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  for (int i = i0; i < i1; ++i) {
    double y0 = 0, y1 = 0, y2 = 0;
    for (int b = start[i]; b < start[i + 1]; ++b) {
      const double* m = val + 5 * static_cast<std::size_t>(b);
      const double* xj = x + s * col[b];
      const double a = xj[0], c = xj[o];
      y0 += m[0] * a + m[2] * c;
      y1 += m[1] * a + m[3] * c;
      y2 += m[4] * xj[2 * o];
    }
    dot += storeRow(x, y, s, o, i, y0, y1, y2);
  }
  return dot;
}

#if defined(__GNUC__) && defined(__x86_64__)
/// splitRows() with the in-plane pair of a block in one SSE2 register
/// (baseline x86-64): [y0, y1] += [a00, a10] x0 + [a01, a11] x1, the same
/// multiplications and additions in the same order, so the same bits.
double splitRowsSse2(const int* start, const int* col, const double* val, const double* x,
                     double* y, std::ptrdiff_t s, std::ptrdiff_t o, int i0, int i1) {
  double dot = 0;
  for (int i = i0; i < i1; ++i) {
    __m128d acc = _mm_setzero_pd();
    double y2 = 0;
    for (int b = start[i]; b < start[i + 1]; ++b) {
      const double* m = val + 5 * static_cast<std::size_t>(b);
      const double* xj = x + s * col[b];
      acc = _mm_add_pd(acc, _mm_add_pd(_mm_mul_pd(_mm_loadu_pd(m), _mm_load1_pd(xj)),
                                       _mm_mul_pd(_mm_loadu_pd(m + 2), _mm_load1_pd(xj + o))));
      y2 += m[4] * xj[2 * o];
    }
    dot +=
        storeRow(x, y, s, o, i, _mm_cvtsd_f64(acc), _mm_cvtsd_f64(_mm_unpackhi_pd(acc, acc)), y2);
  }
  return dot;
}
#endif

#if defined(__GNUC__) && defined(__x86_64__)
#define LAMINA_AVX_BLOCKS 1
/// plainRowsScalar() with the three rows of a block in one AVX register:
/// the same multiplications and additions in the same order per component
/// (AVX without FMA: no contraction), so the same bits.
__attribute__((target("avx"))) double plainRowsAvx(const int* start, const int* col,
                                                   const double* val, const double* x, double* y,
                                                   std::ptrdiff_t s, std::ptrdiff_t o, int i0,
                                                   int i1) {
  double dot = 0;
  for (int i = i0; i < i1; ++i) {
    __m256d acc = _mm256_setzero_pd();
    for (int b = start[i]; b < start[i + 1]; ++b) {
      const double* m = val + 9 * static_cast<std::size_t>(b);
      const double* xj = x + s * col[b];
      __m256d t = _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(m), _mm256_broadcast_sd(xj)),
                                _mm256_mul_pd(_mm256_loadu_pd(m + 3), _mm256_broadcast_sd(xj + o)));
      t = _mm256_add_pd(t, _mm256_mul_pd(_mm256_loadu_pd(m + 6), _mm256_broadcast_sd(xj + 2 * o)));
      acc = _mm256_add_pd(acc, t);
    }
    alignas(32) double v[4];
    _mm256_store_pd(v, acc);
    dot += storeRow(x, y, s, o, i, v[0], v[1], v[2]);
  }
  return dot;
}
#endif

/// The kernel BlockMatrix::useKernel chose.
BlockKernel g_kernel = BlockKernel::Fastest;

/// Below this many node rows threads cost more than they save.
constexpr int kParallelNodes = 10000;

} // namespace

void toPlanar(const double* a, double* p, int n, int i0, int i1) {
  for (int i = i0; i < i1; ++i)
    for (int c = 0; c < 3; ++c)
      p[static_cast<std::ptrdiff_t>(c) * n + i] = a[3 * static_cast<std::ptrdiff_t>(i) + c];
}

void fromPlanar(const double* p, double* a, int n, int i0, int i1) {
  for (int i = i0; i < i1; ++i)
    for (int c = 0; c < 3; ++c)
      a[3 * static_cast<std::ptrdiff_t>(i) + c] = p[static_cast<std::ptrdiff_t>(c) * n + i];
}

void BlockMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  if (kind_.empty())
    product<false>(x, y);
  else
    productViaPlanar<false>(x, y);
}

double BlockMatrix::multiplyDot(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  return kind_.empty() ? product<true>(x, y) : productViaPlanar<true>(x, y);
}

double BlockMatrix::multiplyPlanar(const double* x, double* y, int begin, int end) const {
  const int n = n_;
  if (!kind_.empty()) {
    double dot = 0;
    forEachRun(begin, end, [&](int b, int e, int row) {
      dot += runProduct(koff_.data() + kstart_[row], kval_.data() + 9 * std::size_t(kstart_[row]),
                        kstart_[row + 1] - kstart_[row], n, x, y, b, e);
    });
    return dot;
  }
  // Plain blocks: one node at a time, columns gathered from the three planes.
  return plainRows(x, y, 1, n, begin, end);
}

void BlockMatrix::useKernel(BlockKernel kernel) {
  g_kernel = kernel;
}

double BlockMatrix::plainRows(const double* x, double* y, std::ptrdiff_t s, std::ptrdiff_t o,
                              int begin, int end) const {
  if (split_) {
#if defined(__GNUC__) && defined(__x86_64__)
    if (g_kernel == BlockKernel::Fastest)
      return splitRowsSse2(start_.data(), col_.data(), val_.data(), x, y, s, o, begin, end);
#endif
    return splitRows(start_.data(), col_.data(), val_.data(), x, y, s, o, begin, end);
  }
#ifdef LAMINA_AVX_BLOCKS
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx && g_kernel == BlockKernel::Fastest)
    return plainRowsAvx(start_.data(), col_.data(), val_.data(), x, y, s, o, begin, end);
#endif
  return plainRowsScalar(start_.data(), col_.data(), val_.data(), x, y, s, o, begin, end);
}

template <bool Dot>
double BlockMatrix::productViaPlanar(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const int n = n_;
  y.resize(3 * n);
  xs_.resize(3 * static_cast<std::size_t>(n));
  ys_.resize(3 * static_cast<std::size_t>(n));
  double dot = 0;
#pragma omp parallel reduction(+ : dot) if (n > kParallelNodes)
  {
    const auto [b, e] = core::threadRange(n);
    toPlanar(x.data(), xs_.data(), n, b, e);
#pragma omp barrier
    const double d = multiplyPlanar(xs_.data(), ys_.data(), b, e);
    if (Dot)
      dot += d;
    fromPlanar(ys_.data(), y.data(), n, b, e);
  }
  return dot;
}

template <bool Dot>
double BlockMatrix::product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // Plain storage, interleaved vectors: each thread its contiguous rows.
  const int n = nodes();
  y.resize(3 * n);
  double dot = 0;
#pragma omp parallel reduction(+ : dot) if (n > kParallelNodes)
  {
    const auto [b, e] = core::threadRange(n);
    const double d = plainRows(x.data(), y.data(), 3, 1, b, e);
    if (Dot)
      dot += d;
  }
  return dot;
}

Eigen::Matrix3d BlockMatrix::diagonalBlock(int i) const {
  // Shared rows store column offsets (diagonal = 0), plain rows columns (= i).
  const bool shared = !kind_.empty();
  const int t = shared ? kind_[i] : i;
  const std::vector<int>& start = shared ? kstart_ : start_;
  const std::vector<int>& cols = shared ? koff_ : col_;
  const std::vector<double>& vals = shared ? kval_ : val_;
  const int diagonal = shared ? 0 : i;
  for (int b = start[t]; b < start[t + 1]; ++b)
    if (cols[b] == diagonal) {
      if (split_) {
        const double* m = vals.data() + 5 * b;
        Eigen::Matrix3d d;
        d << m[0], m[2], 0, m[1], m[3], 0, 0, 0, m[4];
        return d;
      }
      if (shared) // row-major
        return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(vals.data() + 9 * b);
      return Eigen::Map<const Eigen::Matrix3d>(vals.data() + 9 * b); // column-major
    }
  return Eigen::Matrix3d::Zero();
}

} // namespace lamina::membrane
