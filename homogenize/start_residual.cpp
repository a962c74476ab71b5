#include "homogenize/start_residual.hpp"

#include "core/error.hpp"
#include "homogenize/stencil.hpp"

#include <omp.h>

#include <algorithm>
#include <type_traits>

namespace lamina::homogenize {

StartResidual::StartResidual(const Grid& grid, const std::vector<std::int32_t>& phase,
                             const std::vector<materials::Stiffness>& C, const Distribution& dist)
    : grid_(grid), dist_(dist), phase_(phase) {
  LAMINA_CHECK(phase_.size() == dist.localSize(), "phase map has ", phase_.size(),
               " voxels, the grid (slab) ", dist.localSize());
  phase_lo_.resize(dist.planeSize());
  std::vector<std::int32_t> unused(dist.planeSize());
  dist.exchangeHalo(phase_.data(), phase_lo_.data(), unused.data());
  for (const auto& c : C)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        C_.push_back(c(i, j));
  const std::size_t n1 = static_cast<std::size_t>(grid.n[1]),
                    n2 = static_cast<std::size_t>(grid.n[2]);
  const long rows = (static_cast<long>(dist.nx()) + 1) * static_cast<long>(n1);
  row_phase_.resize(static_cast<std::size_t>(rows));
#pragma omp parallel for schedule(static)
  for (long r = 0; r < rows; ++r) {
    const std::size_t ur = static_cast<std::size_t>(r);
    const std::int32_t* row = ur < n1 ? phase_lo_.data() + ur * n2 : phase_.data() + (ur - n1) * n2;
    bool uniform = true;
    for (std::size_t k = 1; k < n2; ++k)
      uniform = uniform && row[k] == row[0];
    row_phase_[ur] = uniform ? row[0] : -1;
  }
}

double StartResidual::activeRowFraction() const {
  const int n0 = dist_.nx(), n1 = grid_.n[1];
  std::size_t active = 0;
  for (int i = 0; i < n0; ++i)
    for (int j = 0; j < n1; ++j) {
      const int jm = j == 0 ? n1 - 1 : j - 1;
      const std::int32_t* below = &row_phase_[static_cast<std::size_t>(i) * n1];
      const std::int32_t* above = below + n1;
      const std::int32_t p = above[j];
      active += !(p >= 0 && above[jm] == p && below[j] == p && below[jm] == p);
    }
  return static_cast<double>(active) / (static_cast<double>(n0) * n1);
}

template <class V>
void StartResidual::apply(const std::array<double, 6>& E, V* b,
                          std::array<double, 6>& average) const {
  // per phase the stress C_p (-E), formed as CellOperator forms it with u =
  // 0: b = D^T C (-E) is the exact negation of -D^T C E
  const std::array<double, 6> mE{-E[0], -E[1], -E[2], -E[3], -E[4], -E[5]};
  const std::size_t phases = C_.size() / 36;
  std::vector<double> table(6 * phases);
  for (std::size_t ph = 0; ph < phases; ++ph) {
    const double* Cp = &C_[36 * ph];
    for (int a = 0; a < 6; ++a) {
      const double* rowC = Cp + 6 * a;
      table[6 * ph + static_cast<std::size_t>(a)] = rowC[0] * mE[0] + rowC[1] * mE[1] +
                                                    rowC[2] * mE[2] + rowC[3] * mE[3] +
                                                    rowC[4] * mE[4] + rowC[5] * mE[5];
    }
  }
  const int n0 = dist_.nx(), n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = dist_.localSize(), plane = dist_.planeSize();
  const std::size_t L = stencil::rowLength(grid_), block = stencil::kXCombinations * L;
  const std::size_t un2 = static_cast<std::size_t>(n2);
  const int nt = std::max(1, std::min(omp_get_max_threads(), n0));
  std::vector<std::array<double, 6>> partial(static_cast<std::size_t>(nt));
#pragma omp parallel num_threads(nt)
  {
    // stress rows of the voxel rows below and above a node plane (6 x n2
    // each), two rows of x-combinations, and (float) one force row of 3 x n2
    std::vector<double> scratch(12 * un2 + 2 * block + 3 * un2);
    double* S = scratch.data();
    double* cj = S + 12 * un2;
    double* cm = cj + block;
    double* frow = cm + block;
    const double *prev[6], *cur[6];
    for (int a = 0; a < 6; ++a) {
      prev[a] = S + static_cast<std::size_t>(a) * un2;
      cur[a] = S + static_cast<std::size_t>(6 + a) * un2;
    }
    // the stresses of voxel row j of the planes below and above node plane
    // i, and their x-combinations into out
    auto combine = [&](int i, int j, double* out) {
      const std::int32_t* below =
          i == 0 ? phase_lo_.data() + static_cast<std::size_t>(j) * un2
                 : phase_.data() + (static_cast<std::size_t>(i - 1) * static_cast<std::size_t>(n1) +
                                    static_cast<std::size_t>(j)) *
                                       un2;
      const std::int32_t* above =
          phase_.data() + (static_cast<std::size_t>(i) * static_cast<std::size_t>(n1) +
                           static_cast<std::size_t>(j)) *
                              un2;
      for (std::size_t k = 0; k < un2; ++k) {
        const double* sb = &table[6 * static_cast<std::size_t>(below[k])];
        const double* sa = &table[6 * static_cast<std::size_t>(above[k])];
        for (std::size_t a = 0; a < 6; ++a) {
          S[a * un2 + k] = sb[a];
          S[(6 + a) * un2 + k] = sa[a];
        }
      }
      stencil::xCombinations(prev, cur, n2, out);
    };
    double acc[6] = {0, 0, 0, 0, 0, 0};
#pragma omp for schedule(static)
    for (int i = 0; i < n0; ++i) {
      // <C E>: voxel plane i in the cell operator's order
      const std::int32_t* ph = phase_.data() + static_cast<std::size_t>(i) * plane;
      for (std::size_t v = 0; v < plane; ++v) {
        const double* sv = &table[6 * static_cast<std::size_t>(ph[v])];
        for (int a = 0; a < 6; ++a)
          acc[a] += sv[a];
      }
      // node rows of plane i: zero unless next to an interface
      const std::int32_t* rp_below = &row_phase_[static_cast<std::size_t>(i) * n1];
      const std::int32_t* rp_above = rp_below + n1;
      bool have_previous = false; // cm holds the combinations of row j - 1
      for (int j = 0; j < n1; ++j) {
        const int jm = j == 0 ? n1 - 1 : j - 1;
        const std::size_t row = (static_cast<std::size_t>(i) * n1 + j) * un2;
        V* const out[3] = {b + row, b + N + row, b + 2 * N + row};
        const std::int32_t p = rp_above[j];
        if (p >= 0 && rp_above[jm] == p && rp_below[j] == p && rp_below[jm] == p) {
          for (V* o : out)
            std::fill(o, o + un2, V(0));
          have_previous = false;
          continue;
        }
        if (!have_previous)
          combine(i, jm, cm);
        combine(i, j, cj);
        if constexpr (std::is_same_v<V, double>) {
          stencil::divergenceFromCombinations(cj, cm, grid_, out);
        } else {
          double* const f[3] = {frow, frow + un2, frow + 2 * un2};
          stencil::divergenceFromCombinations(cj, cm, grid_, f);
          for (int c = 0; c < 3; ++c)
            for (std::size_t k = 0; k < un2; ++k)
              out[c][k] = static_cast<V>(f[c][k]);
        }
        std::swap(cj, cm);
        have_previous = true;
      }
    }
    for (int a = 0; a < 6; ++a)
      partial[static_cast<std::size_t>(omp_get_thread_num())][static_cast<std::size_t>(a)] = acc[a];
  }
  // <C E> = -<C (-E)>, summed as the cell operator sums it
  double total[6] = {0, 0, 0, 0, 0, 0};
  for (const auto& p : partial)
    for (int a = 0; a < 6; ++a)
      total[a] += p[static_cast<std::size_t>(a)];
  dist_.sum(total, 6);
  for (std::size_t a = 0; a < 6; ++a)
    average[a] = -(total[a] / static_cast<double>(grid_.size()));
}

template void StartResidual::apply<double>(const std::array<double, 6>&, double*,
                                           std::array<double, 6>&) const;
template void StartResidual::apply<float>(const std::array<double, 6>&, float*,
                                          std::array<double, 6>&) const;

} // namespace lamina::homogenize
