#include "homogenize/start_residual.hpp"

#include "core/error.hpp"
#include "homogenize/stencil.hpp"

#include <omp.h>

#include <algorithm>

namespace lamina::homogenize {

StartResidual::StartResidual(const Grid& grid, const std::vector<std::int32_t>& phase,
                             const std::vector<materials::Stiffness>& C, const Distribution& dist)
    : grid_(grid), dist_(dist), phase_(phase), C_(C) {
  LAMINA_CHECK(phase_.size() == dist.localSize(), "phase map has ", phase_.size(),
               " voxels, the grid (slab) ", dist.localSize());
  phase_lo_.resize(dist.planeSize());
  std::vector<std::int32_t> unused(dist.planeSize());
  dist.exchangeHalo(phase_.data(), phase_lo_.data(), unused.data());
  const std::size_t n1 = static_cast<std::size_t>(grid.n[1]),
                    n2 = static_cast<std::size_t>(grid.n[2]);
  const long rows = (static_cast<long>(dist.nx()) + 1) * static_cast<long>(n1);
  row_phase_.resize(static_cast<std::size_t>(rows));
#pragma omp parallel for schedule(static)
  for (long r = 0; r < rows; ++r) {
    const std::size_t ur = static_cast<std::size_t>(r);
    const std::int32_t* row = ur < n1 ? phase_lo_.data() + ur * n2 : phase_.data() + (ur - n1) * n2;
    std::size_t k = 1;
    while (k < n2 && row[k] == row[0])
      ++k;
    row_phase_[ur] = k == n2 ? row[0] : -1;
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
  const std::size_t phases = C_.size();
  std::vector<double> table(6 * phases);
  for (std::size_t ph = 0; ph < phases; ++ph) {
    const materials::Stiffness& c = C_[ph];
    for (int a = 0; a < 6; ++a)
      table[6 * ph + static_cast<std::size_t>(a)] = c(a, 0) * mE[0] + c(a, 1) * mE[1] +
                                                    c(a, 2) * mE[2] + c(a, 3) * mE[3] +
                                                    c(a, 4) * mE[4] + c(a, 5) * mE[5];
  }
  const int n0 = dist_.nx(), n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = dist_.localSize(), plane = dist_.planeSize();
  const std::size_t L = stencil::rowLength(grid_), block = stencil::kXCombinations * L;
  const std::size_t un2 = static_cast<std::size_t>(n2);
  const int nt = std::max(1, std::min(omp_get_max_threads(), n0));
  std::vector<std::array<double, 6>> partial(static_cast<std::size_t>(nt));
  // stress rows of the voxels below and above a node plane (6 x n2 each),
  // the x-combinations of two voxel rows and one node row of forces, and the
  // phase of each uniform voxel column (-1 if not): per thread, allocated
  // before the region (nothing in it throws)
  std::vector<std::vector<double>> scratch_of(static_cast<std::size_t>(nt),
                                              std::vector<double>(12 * un2 + 2 * block + 3 * un2));
  std::vector<std::vector<std::int32_t>> column_of(static_cast<std::size_t>(nt),
                                                   std::vector<std::int32_t>(un2));
#pragma omp parallel num_threads(nt)
  {
    std::vector<double>& scratch = scratch_of[static_cast<std::size_t>(omp_get_thread_num())];
    double* S = scratch.data();
    double* cj = S + 12 * un2;
    double* cm = cj + block;
    double* const f[3] = {cm + block, cm + block + un2, cm + block + 2 * un2};
    const double *prev[6], *cur[6];
    for (int a = 0; a < 6; ++a) {
      prev[a] = S + static_cast<std::size_t>(a) * un2;
      cur[a] = S + static_cast<std::size_t>(6 + a) * un2;
    }
    // the stresses of voxels k0 .. k0 + m - 1 of the voxel rows below and
    // above, and their x-combinations into out
    auto combine = [&](const std::int32_t* below, const std::int32_t* above, int k0, int m,
                       double* out) {
      for (int t = 0; t < m; ++t) {
        const std::size_t ut = static_cast<std::size_t>(t);
        const double* sb = &table[6 * static_cast<std::size_t>(below[k0 + t])];
        const double* sa = &table[6 * static_cast<std::size_t>(above[k0 + t])];
        for (std::size_t a = 0; a < 6; ++a) {
          S[a * un2 + ut] = sb[a];
          S[(6 + a) * un2 + ut] = sa[a];
        }
      }
      stencil::xCombinations(prev, cur, m, out);
    };
    auto voxelRow = [&](int i, int j) { // voxel row j of plane i (-1: the halo)
      const std::size_t r = static_cast<std::size_t>(i + 1) * static_cast<std::size_t>(n1) +
                            static_cast<std::size_t>(j);
      return r < static_cast<std::size_t>(n1)
                 ? phase_lo_.data() + r * un2
                 : phase_.data() + (r - static_cast<std::size_t>(n1)) * un2;
    };
    std::vector<std::int32_t>& column = column_of[static_cast<std::size_t>(omp_get_thread_num())];
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
      for (int j = 0; j < n1; ++j) {
        const int jm = j == 0 ? n1 - 1 : j - 1;
        const std::size_t row = (static_cast<std::size_t>(i) * n1 + j) * un2;
        V* const out[3] = {b + row, b + N + row, b + 2 * N + row};
        for (V* o : out)
          std::fill(o, o + un2, V(0));
        const std::int32_t p = rp_above[j];
        if (p >= 0 && rp_above[jm] == p && rp_below[j] == p && rp_below[jm] == p)
          continue;
        // node k is zero when voxel columns k - 1 and k are uniform in one phase
        const std::int32_t *bj = voxelRow(i - 1, j), *bm = voxelRow(i - 1, jm),
                           *aj = voxelRow(i, j), *am = voxelRow(i, jm);
        for (int k = 0; k < n2; ++k) {
          const std::int32_t v = aj[k];
          column[static_cast<std::size_t>(k)] = am[k] == v && bj[k] == v && bm[k] == v ? v : -1;
        }
        auto zero = [&](int k) {
          const std::int32_t v = column[static_cast<std::size_t>(k)];
          return v >= 0 && v == column[static_cast<std::size_t>(k == 0 ? n2 - 1 : k - 1)];
        };
        // forces of nodes [k0, k1) from voxels k0 - 1 .. k1 - 1 into f
        // (the whole periodic row when node 0 is among them)
        auto nodes = [&](int k0, int k1) {
          Grid g = grid_;
          int first = 0, m = n2;
          if (k0 > 0) {
            first = k0 - 1;
            m = k1 - k0 + 1;
            g.n[2] = m;
          }
          combine(bj, aj, first, m, cj);
          combine(bm, am, first, m, cm);
          stencil::divergenceFromCombinations(cj, cm, g, f);
          const int shift = k0 > 0 ? k0 - 1 : 0; // f[t] is node t + shift
          for (int c = 0; c < 3; ++c)
            for (int k = k0; k < k1; ++k)
              out[c][k] = static_cast<V>(f[c][k - shift]);
        };
        if (!zero(0)) {
          nodes(0, n2);
          continue;
        }
        for (int k0 = 1; k0 < n2;) {
          if (zero(k0)) {
            ++k0;
            continue;
          }
          int k1 = k0 + 1;
          while (k1 < n2 && !zero(k1))
            ++k1;
          nodes(k0, k1);
          k0 = k1;
        }
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
