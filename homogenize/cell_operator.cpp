#include "homogenize/cell_operator.hpp"

#include "core/error.hpp"
#include "homogenize/stencil.hpp"

#include <omp.h>

#include <algorithm>

namespace lamina::homogenize {

CellOperator::CellOperator(const Grid& grid, std::vector<std::int32_t> phase,
                           const std::vector<materials::Stiffness>& C, const Distribution& dist)
    : grid_(grid), dist_(dist), phase_(std::move(phase)) {
  LAMINA_CHECK(phase_.size() == dist.localSize(), "phase map has ", phase_.size(),
               " voxels, the grid (slab) ", dist.localSize());
  phase_lo_.resize(dist.planeSize());
  std::vector<std::int32_t> unused(dist.planeSize());
  dist.exchangeHalo(phase_.data(), phase_lo_.data(), unused.data());
  for (auto* halo : {&work_d_.halo_lo, &work_d_.halo_hi})
    halo->resize(3 * dist.planeSize());
  for (auto* halo : {&work_f_.halo_lo, &work_f_.halo_hi})
    halo->resize(3 * dist.planeSize());
  for (const auto& c : C)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        C_.push_back(c(i, j));
  // isotropic phases take a 10-flop stress instead of the 36-flop 6x6 product;
  // a pore (C = 0) is isotropic with lambda = mu = 0, a laminate with a pore
  // ply (singular, mu or the bulk modulus may vanish) is not
  for (const auto& c : C) {
    const double lambda = c(0, 1), mu = c(3, 3);
    bool is_iso = c.matrix().isZero(0.0);
    if (!is_iso && mu > 0 && 3 * lambda + 2 * mu > 0) {
      const materials::Matrix6 iso = materials::Stiffness::fromLame(lambda, mu).matrix();
      is_iso =
          (c.matrix() - iso).cwiseAbs().maxCoeff() <= 1e-14 * c.matrix().cwiseAbs().maxCoeff();
    }
    iso_.push_back(is_iso ? 1 : 0);
    lame_.push_back(is_iso ? lambda : 0.0);
    lame_.push_back(is_iso ? mu : 0.0);
  }
  lame_f_.assign(lame_.begin(), lame_.end());
  for (std::int32_t p : phase_lo_)
    LAMINA_CHECK(p >= 0 && static_cast<std::size_t>(p) < C.size(), "phase index ", p,
                 " has no stiffness");
  for (std::int32_t p : phase_)
    LAMINA_CHECK(p >= 0 && static_cast<std::size_t>(p) < C.size(), "phase index ", p,
                 " has no stiffness");
  // the sparse list of anisotropic voxels per row, halo plane first
  const std::size_t n1 = static_cast<std::size_t>(grid.n[1]),
                    n2 = static_cast<std::size_t>(grid.n[2]);
  const std::size_t rows = (static_cast<std::size_t>(dist.nx()) + 1) * n1;
  aniso_start_.reserve(rows + 1);
  for (std::size_t r = 0; r < rows; ++r) {
    aniso_start_.push_back(aniso_k_.size());
    const std::int32_t* row = r < n1 ? phase_lo_.data() + r * n2 : phase_.data() + (r - n1) * n2;
    for (std::size_t k = 0; k < n2; ++k)
      if (!iso_[static_cast<std::size_t>(row[k])])
        aniso_k_.push_back(static_cast<std::int32_t>(k));
  }
  aniso_start_.push_back(aniso_k_.size());
  // the stress planes are sized by apply() for the number of threads it runs with
}

template <>
CellOperator::Work<double>& CellOperator::work<double>() const {
  return work_d_;
}
template <>
CellOperator::Work<float>& CellOperator::work<float>() const {
  return work_f_;
}
template <>
const double* CellOperator::lame<double>() const {
  return lame_.data();
}
template <>
const float* CellOperator::lame<float>() const {
  return lame_f_.data();
}

// Row j of component c of node plane p (local; -1 and nx are the halo planes).
template <class T>
const T* CellOperator::nodeRow(const T* u, int c, int p, int j) const {
  const std::size_t n2 = static_cast<std::size_t>(grid_.n[2]), plane = dist_.planeSize();
  const std::size_t off = static_cast<std::size_t>(c) * plane + static_cast<std::size_t>(j) * n2;
  if (p < 0)
    return work<T>().halo_lo.data() + off;
  if (p >= dist_.nx())
    return work<T>().halo_hi.data() + off;
  return u + static_cast<std::size_t>(c) * dist_.localSize() + static_cast<std::size_t>(p) * plane +
         static_cast<std::size_t>(j) * n2;
}

// Stress of voxel plane i (local, -1 .. nx-1; spanning nodes i and i+1) into S
// (structure of arrays: component a of voxel (j, k) at S[a*componentStride() + j*n2 + k]).
// The strain comes from the shared stencil (stencil.hpp: column sums of the
// four node rows in scratch rows 0-8, finished along z per voxel; 10
// additions per component instead of 21).
template <class T>
void CellOperator::stressPlane(int i, const T* u, const std::array<T, 6>& E, T* S, double* acc,
                               double* energy, T* scratch) const {
  const int n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t P = componentStride();
  const std::size_t L = stencil::rowLength(grid_); // one wrapped column
  const std::int32_t* phase =
      i < 0 ? phase_lo_.data() : phase_.data() + static_cast<std::size_t>(i) * dist_.planeSize();
  for (int j = 0; j < n1; ++j) {
    const int j1 = (j + 1 == n1) ? 0 : j + 1;
    if (u) {
      for (int c = 0; c < 3; ++c)
        stencil::gradientSums(nodeRow(u, c, i, j), nodeRow(u, c, i + 1, j), nodeRow(u, c, i, j1),
                              nodeRow(u, c, i + 1, j1), n2, scratch + (3 * c + 0) * L,
                              scratch + (3 * c + 1) * L, scratch + (3 * c + 2) * L);
    }
    const std::size_t row = static_cast<std::size_t>(j) * n2;
    if (u) {
      isotropicRow(phase + row, E, S + row, acc, energy, scratch);
      anisotropicVoxels(static_cast<std::size_t>(i + 1) * n1 + j, phase + row, E, S + row, acc,
                        energy, scratch);
      continue;
    }
    // u = 0: the strain is E, the stress C_p E and energy of each phase p
    // come from the table uniform_ (the same products, formed once per phase)
    for (int k = 0; k < n2; ++k) {
      const double* sv = &uniform_[7 * static_cast<std::size_t>(phase[row + k])];
      for (int a = 0; a < 6; ++a) {
        S[a * P + row + k] = static_cast<T>(sv[a]);
        if (acc)
          acc[a] += sv[a];
      }
      if (energy)
        *energy += sv[6];
    }
  }
}

// The stress of one voxel of phase ph: the full 6x6 product (lamina order).
void CellOperator::stress6x6(std::size_t ph, const double e[6], double sv[6]) const {
  const double* Cp = &C_[36 * ph];
  for (int a = 0; a < 6; ++a) {
    const double* rowC = Cp + 6 * a;
    sv[a] = rowC[0] * e[0] + rowC[1] * e[1] + rowC[2] * e[2] + rowC[3] * e[3] + rowC[4] * e[4] +
            rowC[5] * e[5];
  }
}

// The stress row from the column sums in scratch, as if every phase were
// isotropic: the phase moduli are gathered into two rows first (zero for an
// anisotropic phase, whose voxels anisotropicVoxels() sets afterwards), so
// the loop over the voxels has no branch and no indirection and runs in
// SIMD lanes (omp simd lets the sums of <sigma> and the energy be reordered).
template <class T>
void CellOperator::isotropicRow(const std::int32_t* phase, const std::array<T, 6>& E, T* S,
                                double* acc, double* energy, T* scratch) const {
  const int n2 = grid_.n[2];
  const std::size_t P = componentStride();
  const std::size_t L = stencil::rowLength(grid_);
  T* lam = scratch + 9 * L;
  T* mu = scratch + 10 * L;
  const T* lame_p = lame<T>();
  for (int k = 0; k < n2; ++k) {
    const std::size_t ph = static_cast<std::size_t>(phase[k]);
    lam[k] = lame_p[2 * ph];
    mu[k] = lame_p[2 * ph + 1];
  }
  const stencil::RowSums<T> sums(scratch, L, grid_);
  const std::array<T, 6> Ek = E; // a local copy: the stores to S cannot alias it
  T *S0 = S, *S1 = S + P, *S2 = S + 2 * P, *S3 = S + 3 * P, *S4 = S + 4 * P, *S5 = S + 5 * P;
  // the row's sums in T (float: n2 / 4 terms per SIMD lane), added to the
  // double accumulators per row
  T a0 = 0, a1 = 0, a2 = 0, a3 = 0, a4 = 0, a5 = 0, en = 0;
#pragma omp simd reduction(+ : a0, a1, a2, a3, a4, a5, en)
  for (int k = 0; k < n2; ++k) {
    T e0, e1, e2, e3, e4, e5;
    stencil::strainAt(sums, Ek, k, e0, e1, e2, e3, e4, e5);
    const T lt = lam[k] * (e0 + e1 + e2), m2 = 2 * mu[k];
    const T s0 = lt + m2 * e0, s1 = lt + m2 * e1, s2 = lt + m2 * e2;
    const T s3 = mu[k] * e3, s4 = mu[k] * e4, s5 = mu[k] * e5;
    S0[k] = s0;
    S1[k] = s1;
    S2[k] = s2;
    S3[k] = s3;
    S4[k] = s4;
    S5[k] = s5;
    a0 += s0;
    a1 += s1;
    a2 += s2;
    a3 += s3;
    a4 += s4;
    a5 += s5;
    en += s0 * e0 + s1 * e1 + s2 * e2 + s3 * e3 + s4 * e4 + s5 * e5;
  }
  if (acc) {
    acc[0] += a0;
    acc[1] += a1;
    acc[2] += a2;
    acc[3] += a3;
    acc[4] += a4;
    acc[5] += a5;
  }
  if (energy)
    *energy += en;
}

// The voxels of anisotropic phases in voxel row @p row_index (isotropicRow
// left them zero stress): strain from the same column sums, the 6x6 product,
// and their share of <sigma> and of the energy.
template <class T>
void CellOperator::anisotropicVoxels(std::size_t row_index, const std::int32_t* phase,
                                     const std::array<T, 6>& E, T* S, double* acc, double* energy,
                                     const T* scratch) const {
  const std::size_t begin = aniso_start_[row_index], end = aniso_start_[row_index + 1];
  if (begin == end)
    return;
  const std::size_t P = componentStride();
  const stencil::RowSums<T> sums(scratch, stencil::rowLength(grid_), grid_);
  for (std::size_t at = begin; at < end; ++at) {
    const int k = aniso_k_[at];
    T et[6];
    stencil::strainAt(sums, E, k, et[0], et[1], et[2], et[3], et[4], et[5]);
    const double e[6] = {et[0], et[1], et[2], et[3], et[4], et[5]};
    double sv[6];
    stress6x6(static_cast<std::size_t>(phase[k]), e, sv);
    double w = 0;
    for (int a = 0; a < 6; ++a) {
      S[a * P + static_cast<std::size_t>(k)] = static_cast<T>(sv[a]);
      w += sv[a] * e[a];
      if (acc)
        acc[a] += sv[a];
    }
    if (energy)
      *energy += w;
  }
}

// Nodal forces of node plane i from voxel planes i-1 (prev) and i (cur):
// f = D^T sigma, i.e. f_c = sum over the 8 voxels around the node of the
// transposed gradient weights times sigma_cd. A node is corner 1 of the
// voxel below it and corner 0 of the voxel above it along each axis. The
// sum factorises like the gradient: across x (prev -/+ cur), then across y
// (rows j-1, j), then across z (voxels k-1, k).
template <class T>
void CellOperator::divergencePlane(int i, const T* prev, const T* cur, T* f, T* scratch) const {
  const int n1 = grid_.n[1], n2 = grid_.n[2];
  const std::size_t N = dist_.localSize(), P = componentStride();
  const std::size_t block = stencil::kXCombinations * stencil::rowLength(grid_);
  // the x-combinations of voxel rows j (cj) and j-1 (cm), rolled along y
  T* cj = scratch;
  T* cm = scratch + block;
  auto combine = [&](int j, T* out) {
    const std::size_t rj = static_cast<std::size_t>(j) * n2;
    const T *pj[6], *qj[6];
    for (int a = 0; a < 6; ++a) {
      pj[a] = prev + a * P + rj;
      qj[a] = cur + a * P + rj;
    }
    stencil::xCombinations(pj, qj, n2, out);
  };
  combine(n1 - 1, cm);
  for (int j = 0; j < n1; ++j) {
    combine(j, cj);
    const std::size_t row = (static_cast<std::size_t>(i) * n1 + j) * n2;
    T* const fr[3] = {f + row, f + N + row, f + 2 * N + row};
    stencil::divergenceFromCombinations(cj, cm, grid_, fr);
    std::swap(cj, cm);
  }
}

// Stress planes hold 6 components of n1*n2 values. With power-of-two grids
// the components would sit a multiple of 4 KiB apart and all map to the same
// L1 cache sets (the divergence reads 24 such streams at once); padding each
// component by 24 doubles (192 bytes) spreads them over distinct sets.
std::size_t CellOperator::componentStride() const {
  return static_cast<std::size_t>(grid_.n[1]) * static_cast<std::size_t>(grid_.n[2]) + 24;
}

std::size_t CellOperator::planeStride() const {
  return 6 * componentStride() + 8;
}

void CellOperator::apply(const double* u, const std::array<double, 6>& E, double* f,
                         std::array<double, 6>* average, double* energy) const {
  applyImpl(u, E, f, average, energy);
}

void CellOperator::apply(const float* u, const std::array<double, 6>& E, float* f,
                         std::array<double, 6>* average, double* energy) const {
  applyImpl(u, E, f, average, energy);
}

template <class T>
void CellOperator::applyImpl(const T* u, const std::array<double, 6>& E, T* f,
                             std::array<double, 6>* average, double* energy) const {
  const int n0 = dist_.nx(); // this slab's planes
  Work<T>& work = this->work<T>();
  if (u)
    dist_.exchangeHalo(u, 3, work.halo_lo.data(), work.halo_hi.data());
  std::array<T, 6> Et;
  for (std::size_t a = 0; a < 6; ++a)
    Et[a] = static_cast<T>(E[a]);
  if (!u) { // per phase: the stress C_p E and the energy density E : C_p : E
    const std::size_t phases = C_.size() / 36;
    uniform_.resize(7 * phases);
    const double e[6] = {E[0], E[1], E[2], E[3], E[4], E[5]};
    for (std::size_t ph = 0; ph < phases; ++ph) {
      double* sv = &uniform_[7 * ph];
      stress6x6(ph, e, sv);
      double w = 0;
      for (int a = 0; a < 6; ++a)
        w += sv[a] * e[a];
      sv[6] = w;
    }
  }
  const std::size_t P = planeStride();
  const int nt = std::max(1, std::min(omp_get_max_threads(), n0));
  if (work.planes.size() < 2 * P * static_cast<std::size_t>(nt))
    work.planes.assign(2 * P * static_cast<std::size_t>(nt), T(0));
  double total[6] = {0, 0, 0, 0, 0, 0};
  double total_energy = 0;
  // The x-planes are cut into slabs (4 per thread, handed out dynamically, so
  // a thread on a core shared with other work does fewer of them). A thread
  // rolls two voxel planes of stress through its slab, recomputing the plane
  // below the slab: no barrier inside, 2 planes of memory per thread.
  const int slabs = nt == 1 ? 1 : std::min(n0, 4 * nt);
  // per-thread scratch rows, allocated before the region (nothing in it throws)
  std::vector<std::vector<T>> scratch_of(
      static_cast<std::size_t>(nt),
      std::vector<T>(2 * stencil::kXCombinations * stencil::rowLength(grid_)));
#pragma omp parallel num_threads(nt)
  {
    const int t = omp_get_thread_num();
    double acc[6] = {0, 0, 0, 0, 0, 0};
    double my_energy = 0;
    double* en = energy ? &my_energy : nullptr;
    std::vector<T>& scratch = scratch_of[static_cast<std::size_t>(t)];
#pragma omp for schedule(dynamic, 1) nowait
    for (int slab = 0; slab < slabs; ++slab) {
      const int begin = static_cast<int>(static_cast<long>(n0) * slab / slabs);
      const int end = static_cast<int>(static_cast<long>(n0) * (slab + 1) / slabs);
      T* prev = work.planes.data() + 2 * P * static_cast<std::size_t>(t);
      T* cur = prev + P;
      if (f && begin < end)
        stressPlane(begin - 1, u, Et, prev, nullptr, nullptr, scratch.data());
      for (int i = begin; i < end; ++i) {
        stressPlane(i, u, Et, cur, average ? acc : nullptr, en, scratch.data());
        if (f)
          divergencePlane(i, prev, cur, f, scratch.data());
        std::swap(prev, cur);
      }
    }
#pragma omp critical(lamina_cell_operator_average)
    {
      for (int a = 0; a < 6; ++a)
        total[a] += acc[a];
      total_energy += my_energy;
    }
  }
  double sums[7] = {total[0], total[1], total[2], total[3], total[4], total[5], total_energy};
  if (average || energy)
    dist_.sum(sums, 7);
  for (int a = 0; a < 6; ++a)
    total[a] = sums[a];
  if (energy)
    *energy = sums[6];
  if (average)
    for (int a = 0; a < 6; ++a)
      (*average)[static_cast<std::size_t>(a)] = total[a] / static_cast<double>(grid_.size());
}

} // namespace lamina::homogenize
