#include "membrane/model/block_matrix.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace lamina::membrane {

BlockMatrix::BlockMatrix(const SparseMatrix& A, bool share_rows) {
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
  if (share_rows)
    shareRepeatedRows();
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
  const double* x1 = x + n;
  const double* x2 = x + 2 * static_cast<std::ptrdiff_t>(n);
  double dot = 0;
  for (int i = begin; i < end; ++i) {
    double y0 = 0, y1 = 0, y2 = 0;
    for (int b = start_[i]; b < start_[i + 1]; ++b) {
      const double* m = val_.data() + 9 * static_cast<std::size_t>(b);
      const int j = col_[b];
      const double a = x[j], c = x1[j], d = x2[j];
      y0 += m[0] * a + m[1] * c + m[2] * d;
      y1 += m[3] * a + m[4] * c + m[5] * d;
      y2 += m[6] * a + m[7] * c + m[8] * d;
    }
    y[i] = y0;
    y[n + i] = y1;
    y[2 * static_cast<std::ptrdiff_t>(n) + i] = y2;
    dot += x[i] * y0 + x1[i] * y1 + x2[i] * y2;
  }
  return dot;
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
  // Plain storage, interleaved vectors: the row of node i, absolute columns.
  const int n = nodes();
  y.resize(3 * n);
  const double* xp = x.data();
  double* yp = y.data();
  double dot = 0;
#pragma omp parallel for schedule(static) reduction(+ : dot) if (n > kParallelNodes)
  for (int i = 0; i < n; ++i) {
    double y0 = 0, y1 = 0, y2 = 0;
    for (int b = start_[i]; b < start_[i + 1]; ++b) {
      const double* m = val_.data() + 9 * static_cast<std::size_t>(b);
      const double* xj = xp + 3 * static_cast<std::ptrdiff_t>(col_[b]);
      y0 += m[0] * xj[0] + m[1] * xj[1] + m[2] * xj[2];
      y1 += m[3] * xj[0] + m[4] * xj[1] + m[5] * xj[2];
      y2 += m[6] * xj[0] + m[7] * xj[1] + m[8] * xj[2];
    }
    yp[3 * i] = y0;
    yp[3 * i + 1] = y1;
    yp[3 * i + 2] = y2;
    if (Dot)
      dot += xp[3 * i] * y0 + xp[3 * i + 1] * y1 + xp[3 * i + 2] * y2;
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
    if (cols[b] == diagonal)
      return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(vals.data() + 9 * b);
  return Eigen::Matrix3d::Zero();
}

} // namespace lamina::membrane
