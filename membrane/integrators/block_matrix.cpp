#include "membrane/integrators/block_matrix.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace lamina::membrane {

BlockMatrix::BlockMatrix(const SparseMatrix& A) {
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
  for (int i = 0; i < n; ++i) {
    double scale = 0;
    for (int b = start_[i]; b < start_[i + 1]; ++b)
      for (int q = 0; q < 9; ++q)
        scale = std::max(scale, std::abs(val_[9 * b + q]));
    const double quantum = scale > 0 ? 1e-14 * scale : 1.0;
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
  std::vector<int>().swap(col_);
  std::vector<double>().swap(val_);
  std::vector<int>().swap(start_);
}

void BlockMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  product<false>(x, y);
}

double BlockMatrix::multiplyDot(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  return product<true>(x, y);
}

template <bool Dot>
double BlockMatrix::product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const int n = nodes();
  y.resize(3 * n);
  const double* xp = x.data();
  double* yp = y.data();
  // Shared rows: kind[i] picks the stored row, columns are offsets from i.
  // Plain storage: the row of node i, absolute columns.
  const bool shared = !kind_.empty();
  const int* rowp = shared ? kind_.data() : nullptr;
  const int* ks = shared ? kstart_.data() : start_.data();
  const int* cols = shared ? koff_.data() : col_.data();
  const double* kv = shared ? kval_.data() : val_.data();
  double dot = 0;
#pragma omp parallel for schedule(static) reduction(+ : dot) if (n > 10000)
  for (int i = 0; i < n; ++i) {
    double y0 = 0, y1 = 0, y2 = 0;
    const int t = shared ? rowp[i] : i;
    const std::ptrdiff_t base = shared ? i : 0;
    for (int b = ks[t]; b < ks[t + 1]; ++b) {
      const double* m = kv + 9 * static_cast<std::size_t>(b);
      const double* xj = xp + 3 * (base + cols[b]);
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
