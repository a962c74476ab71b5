#include "homogenize/cell_operator.hpp"

#include "core/error.hpp"

#include <omp.h>

namespace lamina::homogenize {

CellOperator::CellOperator(const Grid& grid, std::vector<std::int32_t> phase,
                           const std::vector<materials::Stiffness>& C)
    : grid_(grid), phase_(std::move(phase)) {
  LAMINA_CHECK(phase_.size() == grid.size(), "phase map has ", phase_.size(),
               " voxels, the grid ", grid.size());
  for (const auto& c : C)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        C_.push_back(c(i, j));
  for (std::int32_t p : phase_)
    LAMINA_CHECK(p >= 0 && static_cast<std::size_t>(p) < C.size(), "phase index ", p,
                 " has no stiffness");
  planes_.assign(2 * 6 * static_cast<std::size_t>(grid.n[1]) * static_cast<std::size_t>(grid.n[2]),
                 0.0);
}

// Stress of voxel plane i (voxels i, spanning nodes i and i+1) into S.
void CellOperator::stressPlane(int i, const double* u, const std::array<double, 6>& E, double* S,
                               double* acc) const {
  const int n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = grid_.size();
  const double cx = 0.25 / grid_.h[0], cy = 0.25 / grid_.h[1], cz = 0.25 / grid_.h[2];
  const int i1 = (i + 1 == grid_.n[0]) ? 0 : i + 1;
#pragma omp for schedule(static)
  for (int j = 0; j < n1; ++j) {
    const int j1 = (j + 1 == n1) ? 0 : j + 1;
    const std::size_t r00 = (static_cast<std::size_t>(i) * n1 + j) * n2;
    const std::size_t r10 = (static_cast<std::size_t>(i1) * n1 + j) * n2;
    const std::size_t r01 = (static_cast<std::size_t>(i) * n1 + j1) * n2;
    const std::size_t r11 = (static_cast<std::size_t>(i1) * n1 + j1) * n2;
    for (int k = 0; k < n2; ++k) {
      const int k1 = (k + 1 == n2) ? 0 : k + 1;
      double g[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; // g[c][d] = d u_c / d x_d
      if (u) {
        for (int c = 0; c < 3; ++c) {
          const double* uc = u + c * N;
          const double v000 = uc[r00 + k], v001 = uc[r00 + k1];
          const double v100 = uc[r10 + k], v101 = uc[r10 + k1];
          const double v010 = uc[r01 + k], v011 = uc[r01 + k1];
          const double v110 = uc[r11 + k], v111 = uc[r11 + k1];
          g[c][0] = cx * ((v100 + v110 + v101 + v111) - (v000 + v010 + v001 + v011));
          g[c][1] = cy * ((v010 + v110 + v011 + v111) - (v000 + v100 + v001 + v101));
          g[c][2] = cz * ((v001 + v101 + v011 + v111) - (v000 + v100 + v010 + v110));
        }
      }
      // lamina order, engineering shear
      const double e[6] = {E[0] + g[0][0],           E[1] + g[1][1],
                           E[2] + g[2][2],           E[3] + g[0][1] + g[1][0],
                           E[4] + g[1][2] + g[2][1], E[5] + g[0][2] + g[2][0]};
      const double* Cp = &C_[36 * static_cast<std::size_t>(phase_[r00 + k])];
      double* s = S + (static_cast<std::size_t>(j) * n2 + k) * 6;
      for (int a = 0; a < 6; ++a) {
        const double* row = Cp + 6 * a;
        s[a] = row[0] * e[0] + row[1] * e[1] + row[2] * e[2] + row[3] * e[3] + row[4] * e[4] +
               row[5] * e[5];
      }
      if (acc)
        for (int a = 0; a < 6; ++a)
          acc[a] += s[a];
    }
  }
}

// Nodal forces of node plane i from voxel planes i-1 (prev) and i (cur):
// f_c = sum over the 8 voxels around the node of the transposed gradient
// weights times sigma_cd. A node is corner 1 of the voxel below it and
// corner 0 of the voxel above it along each axis.
void CellOperator::divergencePlane(int i, const double* prev, const double* cur, double* f) const {
  const int n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = grid_.size();
  const double cx = 0.25 / grid_.h[0], cy = 0.25 / grid_.h[1], cz = 0.25 / grid_.h[2];
#pragma omp for schedule(static)
  for (int j = 0; j < n1; ++j) {
    const int jm = (j == 0) ? n1 - 1 : j - 1;
    const std::size_t row = (static_cast<std::size_t>(i) * n1 + j) * n2;
    for (int k = 0; k < n2; ++k) {
      const int km = (k == 0) ? n2 - 1 : k - 1;
      double fx = 0, fy = 0, fz = 0;
      for (int b = 0; b < 2; ++b) {
        const std::size_t jj = static_cast<std::size_t>(b ? jm : j) * n2;
        const double sy = b ? cy : -cy;
        for (int c = 0; c < 2; ++c) {
          const std::size_t v = (jj + (c ? km : k)) * 6;
          const double sz = c ? cz : -cz;
          const double* p = prev + v; // voxel i-1: node is its corner 1 along x
          const double* q = cur + v;  // voxel i:   node is its corner 0 along x
          double d[6], s[6];
          for (int a = 0; a < 6; ++a) {
            d[a] = cx * (p[a] - q[a]);
            s[a] = p[a] + q[a];
          }
          fx += d[0] + sy * s[3] + sz * s[5];
          fy += d[3] + sy * s[1] + sz * s[4];
          fz += d[5] + sy * s[4] + sz * s[2];
        }
      }
      f[row + k] = fx;
      f[N + row + k] = fy;
      f[2 * N + row + k] = fz;
    }
  }
}

void CellOperator::apply(const double* u, const std::array<double, 6>& E, double* f,
                         std::array<double, 6>* average) const {
  const int n0 = grid_.n[0];
  const std::size_t P = 6 * static_cast<std::size_t>(grid_.n[1]) * static_cast<std::size_t>(grid_.n[2]);
  double total[6] = {0, 0, 0, 0, 0, 0};
  double* base = planes_.data();
#pragma omp parallel
  {
    double acc[6] = {0, 0, 0, 0, 0, 0};
    double* prev = base;
    double* cur = base + P;
    if (f)
      stressPlane(n0 - 1, u, E, prev, nullptr); // the plane below node plane 0 (periodic)
    for (int i = 0; i < n0; ++i) {
      stressPlane(i, u, E, cur, average ? acc : nullptr);
      if (f)
        divergencePlane(i, prev, cur, f);
      std::swap(prev, cur); // every thread swaps alike; the omp for barriers order the planes
    }
    if (average) {
#pragma omp critical(lamina_cell_operator_average)
      for (int a = 0; a < 6; ++a)
        total[a] += acc[a];
    }
  }
  if (average)
    for (int a = 0; a < 6; ++a)
      (*average)[static_cast<std::size_t>(a)] = total[a] / static_cast<double>(grid_.size());
}

} // namespace lamina::homogenize
