#include "membrane/block_matrix.hpp"

#include "core/error.hpp"

namespace lamina::membrane {

BlockMatrix::BlockMatrix(const SparseMatrix& A) {
  LAMINA_CHECK(A.rows() % 3 == 0 && A.rows() == A.cols(), "BlockMatrix needs a 3n x 3n matrix");
  const int n = static_cast<int>(A.rows() / 3);
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
}

void BlockMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const int n = nodes();
  y.resize(3 * n);
  const double* xp = x.data();
  double* yp = y.data();
  const int* col = col_.data();
  const double* val = val_.data();
  const int* start = start_.data();
#pragma omp parallel for schedule(static) if (n > 10000)
  for (int i = 0; i < n; ++i) {
    double y0 = 0, y1 = 0, y2 = 0;
    for (int b = start[i]; b < start[i + 1]; ++b) {
      const double* m = val + 9 * static_cast<size_t>(b);
      const double* xj = xp + 3 * col[b];
      y0 += m[0] * xj[0] + m[1] * xj[1] + m[2] * xj[2];
      y1 += m[3] * xj[0] + m[4] * xj[1] + m[5] * xj[2];
      y2 += m[6] * xj[0] + m[7] * xj[1] + m[8] * xj[2];
    }
    yp[3 * i] = y0;
    yp[3 * i + 1] = y1;
    yp[3 * i + 2] = y2;
  }
}

Eigen::Matrix3d BlockMatrix::diagonalBlock(int i) const {
  for (int b = start_[i]; b < start_[i + 1]; ++b)
    if (col_[b] == i) {
      Eigen::Matrix3d m;
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          m(c, d) = val_[9 * b + 3 * c + d];
      return m;
    }
  return Eigen::Matrix3d::Zero();
}

} // namespace lamina::membrane
