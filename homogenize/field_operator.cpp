#include "homogenize/field_operator.hpp"

#include "homogenize/stencil.hpp"

#include <omp.h>

#include <vector>

namespace lamina::homogenize {

FieldOperator::FieldOperator(const Grid& grid) : grid_(grid) {}

void FieldOperator::strain(const double* u, const std::array<double, 6>& E, double* eps) const {
  const int n0 = grid_.n[0], n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = grid_.size(), L = stencil::rowLength(grid_);
  // per-thread rows, allocated before the region (nothing in it throws)
  std::vector<std::vector<double>> rows_of(static_cast<std::size_t>(omp_get_max_threads()),
                                           std::vector<double>(9 * L));
#pragma omp parallel
  {
    std::vector<double>& sums = rows_of[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (int i = 0; i < n0; ++i) {
      const int i1 = i + 1 == n0 ? 0 : i + 1;
      for (int j = 0; j < n1; ++j) {
        const int j1 = j + 1 == n1 ? 0 : j + 1;
        const std::size_t r00 = (static_cast<std::size_t>(i) * n1 + j) * n2;
        double* rows[6];
        for (int a = 0; a < 6; ++a)
          rows[a] = eps + a * N + r00;
        if (!u) {
          for (int a = 0; a < 6; ++a)
            for (int k = 0; k < n2; ++k)
              rows[a][k] = E[static_cast<std::size_t>(a)];
          continue;
        }
        const std::size_t r10 = (static_cast<std::size_t>(i1) * n1 + j) * n2;
        const std::size_t r01 = (static_cast<std::size_t>(i) * n1 + j1) * n2;
        const std::size_t r11 = (static_cast<std::size_t>(i1) * n1 + j1) * n2;
        for (int c = 0; c < 3; ++c) {
          const double* uc = u + c * N;
          stencil::gradientSums(uc + r00, uc + r10, uc + r01, uc + r11, n2, &sums[(3 * c) * L],
                                &sums[(3 * c + 1) * L], &sums[(3 * c + 2) * L]);
        }
        stencil::strainRow(sums.data(), L, grid_, E, rows);
      }
    }
  }
}

void FieldOperator::divergence(const double* sigma, double* f) const {
  const int n0 = grid_.n[0], n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = grid_.size(), L = stencil::rowLength(grid_);
  std::vector<std::vector<double>> rows_of(static_cast<std::size_t>(omp_get_max_threads()),
                                           std::vector<double>(9 * L));
#pragma omp parallel
  {
    std::vector<double>& scratch = rows_of[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (int i = 0; i < n0; ++i) {
      const int im = i == 0 ? n0 - 1 : i - 1;
      for (int j = 0; j < n1; ++j) {
        const int jm = j == 0 ? n1 - 1 : j - 1;
        // node (i, j, .) is a corner of the voxel rows (i - a, j - b) for a, b in {0, 1}
        const std::size_t rj = (static_cast<std::size_t>(i) * n1 + j) * n2;
        const std::size_t rm = (static_cast<std::size_t>(i) * n1 + jm) * n2;
        const std::size_t pj = (static_cast<std::size_t>(im) * n1 + j) * n2;
        const std::size_t pm = (static_cast<std::size_t>(im) * n1 + jm) * n2;
        const double *prev_j[6], *prev_m[6], *cur_j[6], *cur_m[6];
        for (int a = 0; a < 6; ++a) {
          const double* s = sigma + a * N;
          prev_j[a] = s + pj;
          prev_m[a] = s + pm;
          cur_j[a] = s + rj;
          cur_m[a] = s + rm;
        }
        double* const fr[3] = {f + rj, f + N + rj, f + 2 * N + rj};
        stencil::divergenceRow(prev_j, prev_m, cur_j, cur_m, grid_, scratch.data(), fr);
      }
    }
  }
}

} // namespace lamina::homogenize
