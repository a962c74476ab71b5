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

namespace {

/// Per phase the stress C_p (-E), 6 per phase, formed as CellOperator forms
/// it with u = 0: b = D^T C (-E) is the exact negation of -D^T C E.
std::vector<double> negatedStresses(const std::vector<materials::Stiffness>& C,
                                    const std::array<double, 6>& E) {
  const std::array<double, 6> mE{-E[0], -E[1], -E[2], -E[3], -E[4], -E[5]};
  const std::size_t phases = C.size();
  std::vector<double> table(6 * phases);
  for (std::size_t ph = 0; ph < phases; ++ph) {
    const materials::Stiffness& c = C[ph];
    for (int a = 0; a < 6; ++a)
      table[6 * ph + static_cast<std::size_t>(a)] = c(a, 0) * mE[0] + c(a, 1) * mE[1] +
                                                    c(a, 2) * mE[2] + c(a, 3) * mE[3] +
                                                    c(a, 4) * mE[4] + c(a, 5) * mE[5];
  }
  return table;
}

/// acc += the stresses of the @p count voxels of phases @p ph (in order).
void addStresses(const std::int32_t* ph, std::size_t count, const double* table, double acc[6]) {
  for (std::size_t v = 0; v < count; ++v) {
    const double* sv = &table[6 * static_cast<std::size_t>(ph[v])];
    for (int a = 0; a < 6; ++a)
      acc[a] += sv[a];
  }
}

/// The scratch of one thread: the stress rows of the voxels below and above
/// a node plane (6 x n2 each), the x-combinations of two voxel rows and one
/// node row of forces, and the phase of each uniform voxel column (-1 if
/// not). Allocated before the parallel region (nothing in it throws).
struct RowScratch {
  RowScratch(std::size_t n2, std::size_t block)
      : values(12 * n2 + 2 * block + 3 * n2), column(n2) {}
  std::vector<double> values;
  std::vector<std::int32_t> column;
};

/// The nodal forces b = D^T C (-E) of the node rows of one plane, formed
/// with the stencil functions of the cell operator on the runs of nodes
/// next to an interface; the other nodes are zero-filled.
template <class V>
class RowForces {
public:
  /// @param phase, phase_lo this slab's voxels and the halo plane below;
  /// @param row_phase per voxel row its uniform phase or -1
  /// (StartResidual); @param table negatedStresses(); @param b the forces
  RowForces(const Grid& grid, std::size_t local, const std::int32_t* phase,
            const std::int32_t* phase_lo, const std::int32_t* row_phase, const double* table,
            V* b, RowScratch& scratch)
      : grid_(grid), n1_(grid.n[1]), n2_(grid.n[2]), N_(local), phase_(phase),
        phase_lo_(phase_lo), row_phase_(row_phase), table_(table), b_(b),
        column_(scratch.column.data()) {
    const std::size_t un2 = static_cast<std::size_t>(n2_);
    const std::size_t block = stencil::kXCombinations * stencil::rowLength(grid);
    double* S = scratch.values.data();
    S_ = S;
    cj_ = S + 12 * un2;
    cm_ = cj_ + block;
    for (int c = 0; c < 3; ++c)
      f_[c] = cm_ + block + static_cast<std::size_t>(c) * un2;
    for (int a = 0; a < 6; ++a) {
      prev_[a] = S + static_cast<std::size_t>(a) * un2;
      cur_[a] = S + static_cast<std::size_t>(6 + a) * un2;
    }
  }

  /// Forms the node rows of node plane @p i.
  void plane(int i) {
    const std::int32_t* rp_below = &row_phase_[static_cast<std::size_t>(i) * n1_];
    const std::int32_t* rp_above = rp_below + n1_;
    const std::size_t un2 = static_cast<std::size_t>(n2_);
    for (int j = 0; j < n1_; ++j) {
      const int jm = j == 0 ? n1_ - 1 : j - 1;
      const std::size_t row = (static_cast<std::size_t>(i) * n1_ + j) * un2;
      out_[0] = b_ + row;
      out_[1] = b_ + N_ + row;
      out_[2] = b_ + 2 * N_ + row;
      for (V* o : out_)
        std::fill(o, o + un2, V(0));
      const std::int32_t p = rp_above[j];
      if (p >= 0 && rp_above[jm] == p && rp_below[j] == p && rp_below[jm] == p)
        continue;
      bj_ = voxelRow(i - 1, j);
      bm_ = voxelRow(i - 1, jm);
      aj_ = voxelRow(i, j);
      am_ = voxelRow(i, jm);
      interfaceRow();
    }
  }

private:
  /// voxel row j of plane i (-1: the halo)
  const std::int32_t* voxelRow(int i, int j) const {
    const std::size_t un2 = static_cast<std::size_t>(n2_), un1 = static_cast<std::size_t>(n1_);
    const std::size_t r = static_cast<std::size_t>(i + 1) * un1 + static_cast<std::size_t>(j);
    return r < un1 ? phase_lo_ + r * un2 : phase_ + (r - un1) * un2;
  }

  /// The node row between voxel rows bj_, bm_ (below) and aj_, am_ (above),
  /// one not uniform: its runs of nodes next to an interface.
  void interfaceRow() {
    // node k is zero when voxel columns k - 1 and k are uniform in one phase
    for (int k = 0; k < n2_; ++k) {
      const std::int32_t v = aj_[k];
      column_[k] = am_[k] == v && bj_[k] == v && bm_[k] == v ? v : -1;
    }
    if (!zero(0)) {
      nodes(0, n2_);
      return;
    }
    for (int k0 = 1; k0 < n2_;) {
      if (zero(k0)) {
        ++k0;
        continue;
      }
      int k1 = k0 + 1;
      while (k1 < n2_ && !zero(k1))
        ++k1;
      nodes(k0, k1);
      k0 = k1;
    }
  }

  bool zero(int k) const {
    const std::int32_t v = column_[k];
    return v >= 0 && v == column_[k == 0 ? n2_ - 1 : k - 1];
  }

  /// forces of nodes [k0, k1) from voxels k0 - 1 .. k1 - 1 into the row
  /// (the whole periodic row when node 0 is among them)
  void nodes(int k0, int k1) {
    Grid g = grid_;
    int first = 0, m = n2_;
    if (k0 > 0) {
      first = k0 - 1;
      m = k1 - k0 + 1;
      g.n[2] = m;
    }
    combine(bj_, aj_, first, m, cj_);
    combine(bm_, am_, first, m, cm_);
    stencil::divergenceFromCombinations(cj_, cm_, g, f_);
    const int shift = k0 > 0 ? k0 - 1 : 0; // f[t] is node t + shift
    for (int c = 0; c < 3; ++c)
      for (int k = k0; k < k1; ++k)
        out_[c][k] = static_cast<V>(f_[c][k - shift]);
  }

  /// the stresses of voxels k0 .. k0 + m - 1 of the voxel rows below and
  /// above, and their x-combinations into out
  void combine(const std::int32_t* below, const std::int32_t* above, int k0, int m, double* out) {
    const std::size_t un2 = static_cast<std::size_t>(n2_);
    for (int t = 0; t < m; ++t) {
      const std::size_t ut = static_cast<std::size_t>(t);
      const double* sb = &table_[6 * static_cast<std::size_t>(below[k0 + t])];
      const double* sa = &table_[6 * static_cast<std::size_t>(above[k0 + t])];
      for (std::size_t a = 0; a < 6; ++a) {
        S_[a * un2 + ut] = sb[a];
        S_[(6 + a) * un2 + ut] = sa[a];
      }
    }
    stencil::xCombinations(prev_, cur_, m, out);
  }

  const Grid& grid_;
  int n1_, n2_;
  std::size_t N_;
  const std::int32_t *phase_, *phase_lo_, *row_phase_;
  const double* table_;
  V* b_;
  std::int32_t* column_;
  double *S_, *cj_, *cm_;
  double* f_[3];
  const double *prev_[6], *cur_[6];
  V* out_[3] = {};
  const std::int32_t *bj_ = nullptr, *bm_ = nullptr, *aj_ = nullptr, *am_ = nullptr;
};

} // namespace

template <class V>
void StartResidual::apply(const std::array<double, 6>& E, V* b,
                          std::array<double, 6>& average) const {
  const std::vector<double> table = negatedStresses(C_, E);
  const int n0 = dist_.nx();
  const std::size_t plane = dist_.planeSize();
  const std::size_t block = stencil::kXCombinations * stencil::rowLength(grid_);
  const int nt = std::max(1, std::min(omp_get_max_threads(), n0));
  std::vector<std::array<double, 6>> partial(static_cast<std::size_t>(nt));
  std::vector<RowScratch> scratch_of(static_cast<std::size_t>(nt),
                                     RowScratch(static_cast<std::size_t>(grid_.n[2]), block));
#pragma omp parallel num_threads(nt)
  {
    const std::size_t me = static_cast<std::size_t>(omp_get_thread_num());
    RowForces<V> forces(grid_, dist_.localSize(), phase_.data(), phase_lo_.data(),
                        row_phase_.data(), table.data(), b, scratch_of[me]);
    double acc[6] = {0, 0, 0, 0, 0, 0};
#pragma omp for schedule(static)
    for (int i = 0; i < n0; ++i) {
      // <C E>: voxel plane i in the cell operator's order
      addStresses(phase_.data() + static_cast<std::size_t>(i) * plane, plane, table.data(), acc);
      // node rows of plane i: zero unless next to an interface
      forces.plane(i);
    }
    for (int a = 0; a < 6; ++a)
      partial[me][static_cast<std::size_t>(a)] = acc[a];
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
