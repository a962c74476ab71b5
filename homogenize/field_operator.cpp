#include "homogenize/field_operator.hpp"

namespace lamina::homogenize {

FieldOperator::FieldOperator(const Grid& grid) : grid_(grid) {}

void FieldOperator::strain(const double* u, const std::array<double, 6>& E, double* eps) const {
  const int n0 = grid_.n[0], n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = grid_.size();
  const double cx = 0.25 / grid_.h[0], cy = 0.25 / grid_.h[1], cz = 0.25 / grid_.h[2];
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n0; ++i) {
    const int i1 = i + 1 == n0 ? 0 : i + 1;
    for (int j = 0; j < n1; ++j) {
      const int j1 = j + 1 == n1 ? 0 : j + 1;
      const std::size_t r00 = (static_cast<std::size_t>(i) * n1 + j) * n2;
      const std::size_t r10 = (static_cast<std::size_t>(i1) * n1 + j) * n2;
      const std::size_t r01 = (static_cast<std::size_t>(i) * n1 + j1) * n2;
      const std::size_t r11 = (static_cast<std::size_t>(i1) * n1 + j1) * n2;
      for (int k = 0; k < n2; ++k) {
        const int k1 = k + 1 == n2 ? 0 : k + 1;
        const std::size_t v = r00 + k;
        double e[6] = {E[0], E[1], E[2], E[3], E[4], E[5]};
        if (u) {
          double g[3][3]; // g[c][d] = d u_c / d x_d
          for (int c = 0; c < 3; ++c) {
            const double* uc = u + c * N;
            // corners (a, b, c): u_abc
            const double u000 = uc[r00 + k], u001 = uc[r00 + k1];
            const double u100 = uc[r10 + k], u101 = uc[r10 + k1];
            const double u010 = uc[r01 + k], u011 = uc[r01 + k1];
            const double u110 = uc[r11 + k], u111 = uc[r11 + k1];
            g[c][0] = cx * ((u100 + u101 + u110 + u111) - (u000 + u001 + u010 + u011));
            g[c][1] = cy * ((u010 + u011 + u110 + u111) - (u000 + u001 + u100 + u101));
            g[c][2] = cz * ((u001 + u011 + u101 + u111) - (u000 + u010 + u100 + u110));
          }
          e[0] += g[0][0];
          e[1] += g[1][1];
          e[2] += g[2][2];
          e[3] += g[0][1] + g[1][0];
          e[4] += g[1][2] + g[2][1];
          e[5] += g[0][2] + g[2][0];
        }
        for (int a = 0; a < 6; ++a)
          eps[a * N + v] = e[a];
      }
    }
  }
}

void FieldOperator::divergence(const double* sigma, double* f) const {
  const int n0 = grid_.n[0], n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = grid_.size();
  const double cx = 0.25 / grid_.h[0], cy = 0.25 / grid_.h[1], cz = 0.25 / grid_.h[2];
  // stress components by (row c, column d): lamina order xx yy zz xy yz xz
  static constexpr int kComp[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n0; ++i) {
    const int im = i == 0 ? n0 - 1 : i - 1;
    for (int j = 0; j < n1; ++j) {
      const int jm = j == 0 ? n1 - 1 : j - 1;
      // voxel (i - a, j - b, .) has this node at its corner (a, b, .)
      const std::size_t r00 = (static_cast<std::size_t>(i) * n1 + j) * n2;   // a=0, b=0
      const std::size_t r10 = (static_cast<std::size_t>(im) * n1 + j) * n2;  // a=1, b=0
      const std::size_t r01 = (static_cast<std::size_t>(i) * n1 + jm) * n2;  // a=0, b=1
      const std::size_t r11 = (static_cast<std::size_t>(im) * n1 + jm) * n2; // a=1, b=1
      for (int k = 0; k < n2; ++k) {
        const int km = k == 0 ? n2 - 1 : k - 1;
        for (int c = 0; c < 3; ++c) {
          const double* sx = sigma + kComp[c][0] * N;
          const double* sy = sigma + kComp[c][1] * N;
          const double* sz = sigma + kComp[c][2] * N;
          // sums over the 8 voxels, signed by the node's corner offset
          const double fx = (sx[r10 + k] + sx[r10 + km] + sx[r11 + k] + sx[r11 + km]) -
                            (sx[r00 + k] + sx[r00 + km] + sx[r01 + k] + sx[r01 + km]);
          const double fy = (sy[r01 + k] + sy[r01 + km] + sy[r11 + k] + sy[r11 + km]) -
                            (sy[r00 + k] + sy[r00 + km] + sy[r10 + k] + sy[r10 + km]);
          const double fz = (sz[r00 + km] + sz[r10 + km] + sz[r01 + km] + sz[r11 + km]) -
                            (sz[r00 + k] + sz[r10 + k] + sz[r01 + k] + sz[r11 + k]);
          f[c * N + r00 + k] = cx * fx + cy * fy + cz * fz;
        }
      }
    }
  }
}

} // namespace lamina::homogenize
