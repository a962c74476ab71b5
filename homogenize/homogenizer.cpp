#include "homogenize/homogenizer.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/interrupt.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "homogenize/cell_operator.hpp"
#include "homogenize/cg_solver.hpp"
#include "homogenize/fft.hpp"
#include "homogenize/green_operator.hpp"
#include "homogenize/start_residual.hpp"

#include <Eigen/Eigenvalues>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>

namespace lamina::homogenize {

double Result::maxResidual() const {
  double r = 0;
  for (const auto& c : cases)
    r = std::max(r, c.residual);
  return r;
}

std::array<int, 6> Result::iterations() const {
  std::array<int, 6> it{};
  for (std::size_t k = 0; k < 6; ++k)
    it[k] = cases[k].iterations;
  return it;
}

namespace {

/// @return whether @p c is a pore's stiffness or a laminate with a pore ply:
/// finite, symmetric, positive semi-definite (its smallest eigenvalue at
/// least -1e-10 of its largest: the round-off of a laminate's null space)
bool poreLike(const materials::Stiffness& c) {
  const materials::Matrix6& m = c.matrix();
  if (!m.allFinite() || c.asymmetry() > 1e-10)
    return false;
  if (m.isZero(0.0))
    return true; // a void phase
  Eigen::SelfAdjointEigenSolver<materials::Matrix6> es(m, Eigen::EigenvaluesOnly);
  return es.eigenvalues()(0) >= -1e-10 * es.eigenvalues()(5);
}

} // namespace

void referenceMedium(const std::vector<materials::Stiffness>& C, double& lambda0, double& mu0) {
  double kmin = std::numeric_limits<double>::max(), kmax = 0;
  double gmin = std::numeric_limits<double>::max(), gmax = 0;
  // one 6x6 inversion per phase (composite voxels: tens of thousands of
  // phases), on the threads; min and max do not depend on the order. A
  // singular C (a pore, a laminate with a pore ply) has no Reuss moduli: it
  // enters the maxima only
  const long count = static_cast<long>(C.size());
  long definite = 0;
#pragma omp parallel for schedule(static) reduction(min : kmin, gmin) \
    reduction(max : kmax, gmax) reduction(+ : definite)
  for (long p = 0; p < count; ++p) {
    const auto& c = C[static_cast<std::size_t>(p)];
    kmax = std::max(kmax, materials::voigtBulk(c));
    gmax = std::max(gmax, materials::voigtShear(c));
    if (!c.valid())
      continue;
    ++definite;
    double kr = 0, gr = 0;
    materials::reussModuli(c, kr, gr);
    kmin = std::min(kmin, kr);
    gmin = std::min(gmin, gr);
  }
  LAMINA_CHECK(definite > 0, "the cell is all void: no voxel has a positive definite stiffness");
  const double K0 = std::sqrt(kmin * kmax);
  mu0 = std::sqrt(gmin * gmax);
  lambda0 = K0 - 2.0 * mu0 / 3.0;
}

Precision autoPrecision(double tol) {
  return tol >= 1e-6 ? Precision::Single : Precision::Double;
}

int solverThreads(int requested, std::size_t voxels) {
  return requested > 0 ? requested : voxels < 65536 ? 1 : omp_get_max_threads();
}

bool floatVectors(Precision fft, double tol) {
  return fft == Precision::Single && tol >= kFloatVectorsTol;
}

Homogenizer::Homogenizer(const Grid& grid, std::vector<std::int32_t> phase,
                         std::vector<materials::Stiffness> C, std::vector<double> density,
                         Options options)
    : Homogenizer(grid, Distribution::serial(grid), std::move(phase), std::move(C),
                  std::move(density), options) {}

Homogenizer::Homogenizer(const Grid& grid, const Distribution& dist,
                         std::vector<std::int32_t> phase, std::vector<materials::Stiffness> C,
                         std::vector<double> density, Options options)
    : grid_(grid), dist_(dist), phase_(std::move(phase)), C_(std::move(C)),
      density_(std::move(density)), opt_(options) {
  LAMINA_CHECK(C_.size() == density_.size(), "one density per phase is required");
  LAMINA_CHECK(phase_.size() == dist_.localSize(), "phase map size does not match the grid");
  LAMINA_CHECK(opt_.tol > 0, "tolerance must be positive");
  // one stiffness per composite voxel (tens of thousands): checked on the
  // threads, the first invalid one again to throw its message; a pore (C =
  // 0) and a laminate with a pore ply (positive semi-definite) are valid
  const long phases = static_cast<long>(C_.size());
  long bad = phases;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (long p = 0; p < phases; ++p) {
    const materials::Stiffness& c = C_[static_cast<std::size_t>(p)];
    if (!c.valid() && !poreLike(c))
      bad = std::min(bad, p);
  }
  if (bad < phases)
    C_[static_cast<std::size_t>(bad)].validate("phase " + std::to_string(bad));
}

template <class V>
void Homogenizer::solveCases(const CellOperator& A, const StartResidual& b, const GreenOperator& M,
                             const materials::Stiffness& C0, Result& res, materials::Matrix6& C,
                             materials::Matrix6& C_energy) {
  CgSolver<V> cg(dist_.localSize(), A, M, dist_, static_cast<double>(res.voxels));
  // displacements: all six for the energy estimate, one for a sink
  const bool energy_form = opt_.estimate == Estimate::Energy;
  std::vector<AlignedArray<V>> x;
  for (int k = 0; k < (energy_form ? 6 : sink_ ? 1 : 0); ++k)
    x.emplace_back(3 * dist_.localSize());

  AlignedBuffer x_double; // float solves: x handed to the sink in double

  // solve: six unit strains (lamina order, engineering shear) -> six columns
  core::ProgressLine progress("homogenize", 6, opt_.quiet);
  for (int k = 0; k < 6; ++k) {
    std::array<double, 6> E{0, 0, 0, 0, 0, 0}, sigma{};
    E[static_cast<std::size_t>(k)] = 1.0;
    const double energy = C0.matrix()(k, k); // E^T C0 E for a unit E_k
    const std::string load_case = "load case " + std::to_string(k + 1) + "/6";
    // the line follows the CG iterations (redrawn at most every 0.1 s on a
    // terminal), and each case ends with its own count
    auto monitor = [&](int it, double r) {
      if (monitor_)
        monitor_(k, it, r);
      else
        progress.update(k, load_case + ": CG iteration " + std::to_string(it) + ", residual " +
                               core::formatShort(r, 3));
    };
    try {
      V* xk = x.empty() ? nullptr : x[energy_form ? static_cast<std::size_t>(k) : 0].data();
      res.cases[static_cast<std::size_t>(k)] =
          cg.solve(b, E, energy, opt_.tol, opt_.max_iterations, monitor, &sigma, xk);
    } catch (const DivergenceError& e) {
      throw DivergenceError("load case " + std::to_string(k + 1) + ": " + e.message());
    } catch (const Interrupted&) {
      throw; // a stop, not an error of this case: keeps its type
    } catch (const Error& e) {
      throw Error("load case " + std::to_string(k + 1) + ": " + e.message());
    }
    const LoadCaseResult& solved = res.cases[static_cast<std::size_t>(k)];
    if (!monitor_)
      progress.update(k + 1, load_case + ": " + std::to_string(solved.iterations) +
                                 (solved.iterations == 1 ? " CG iteration" : " CG iterations") +
                                 ", residual " + core::formatShort(solved.residual, 3));
    for (int a = 0; a < 6; ++a)
      C(a, k) = sigma[static_cast<std::size_t>(a)];
    if (energy_form) { // C_jk = <sigma_k>_j - x_j^T r_k / N for the cases j <= k
      double dots[6];
      cg.residualDots(x, k + 1, dots);
      for (int j = 0; j <= k; ++j)
        C_energy(j, k) = C_energy(k, j) = C(j, k) - dots[j] / static_cast<double>(res.voxels);
    }
    if (sink_) {
      const V* xk = x[energy_form ? static_cast<std::size_t>(k) : 0].data();
      if constexpr (std::is_same_v<V, double>) {
        sink_(k, xk);
      } else { // the sink takes double fields
        if (x_double.size() == 0)
          x_double = AlignedBuffer(3 * dist_.localSize());
        double* xd = x_double.data();
        const std::size_t n = x_double.size();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i)
          xd[i] = static_cast<double>(xk[i]);
        sink_(k, xd);
      }
    }
  }
  std::string counts;
  for (int it : res.iterations())
    counts += " " + std::to_string(it);
  progress.finish("CG iterations per load case:" + counts);
}

Result Homogenizer::run() {
  const auto t0 = std::chrono::steady_clock::now();
  const SolverThreads threads(opt_.threads, grid_.size());
  const auto guard = threads.guard();
  Result res;
  res.voxels = grid_.size();

  // setup: phase fractions, density, reference medium, FFT plans
  // voxels per phase, on the threads (integer sums: any order); the first
  // voxel whose phase has no stiffness is reported
  std::vector<std::size_t> count(C_.size(), 0);
  const long voxels = static_cast<long>(phase_.size());
  long bad = voxels;
  // per-thread counts, allocated before the region (nothing in it throws)
  std::vector<std::vector<std::size_t>> counts_of(static_cast<std::size_t>(omp_get_max_threads()),
                                                  std::vector<std::size_t>(C_.size(), 0));
#pragma omp parallel
  {
    std::vector<std::size_t>& mine = counts_of[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(static) reduction(min : bad)
    for (long v = 0; v < voxels; ++v) {
      const std::int32_t p = phase_[static_cast<std::size_t>(v)];
      if (p >= 0 && static_cast<std::size_t>(p) < C_.size())
        ++mine[static_cast<std::size_t>(p)];
      else
        bad = std::min(bad, v);
    }
#pragma omp critical(lamina_homogenizer_phase_count)
    for (std::size_t p = 0; p < count.size(); ++p)
      count[p] += mine[p];
  }
  LAMINA_CHECK(bad == voxels, "phase index ",
               bad < voxels ? phase_[static_cast<std::size_t>(bad)] : 0, " has no stiffness");
  dist_.sum(count.data(), static_cast<int>(count.size()));
  std::vector<materials::Stiffness> present;
  for (std::size_t p = 0; p < C_.size(); ++p) {
    const double f = static_cast<double>(count[p]) / static_cast<double>(res.voxels);
    res.voxel_fraction.push_back(f);
    res.density += f * density_[p];
    if (count[p] > 0)
      present.push_back(C_[p]);
  }
  referenceMedium(present, res.lambda0, res.mu0);
  const materials::Stiffness C0 = materials::Stiffness::fromLame(res.lambda0, res.mu0);
  // FFTW_MEASURE halves the transform time but plans for seconds: worth it
  // above 64^3 (and free once its wisdom is cached on disk)
  const bool measure = opt_.measure > 0 || (opt_.measure < 0 && grid_.size() > (1u << 18));
  res.precision = opt_.precision ? *opt_.precision : autoPrecision(opt_.tol);
  res.estimate = opt_.estimate;
  VectorFft fft(grid_, dist_, threads.count(), measure, res.precision);
  const CellOperator A(grid_, phase_, C_, dist_);
  const StartResidual b(grid_, phase_, C_, dist_);
  const GreenOperator M(grid_, res.lambda0, res.mu0, fft, dist_);
  materials::Matrix6 C = materials::Matrix6::Zero(), C_energy = materials::Matrix6::Zero();
  res.float_vectors = floatVectors(res.precision, opt_.tol);
  if (res.float_vectors)
    solveCases<float>(A, b, M, C0, res, C, C_energy);
  else
    solveCases<double>(A, b, M, C0, res, C, C_energy);

  // output: raw and symmetrized C, diagnostics
  res.C_raw = materials::Stiffness(C);
  res.asymmetry = res.C_raw.asymmetry();
  res.C =
      opt_.estimate == Estimate::Energy ? materials::Stiffness(C_energy) : res.C_raw.symmetrized();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      LAMINA_CHECK(std::isfinite(res.C(i, j)), "effective stiffness is not finite");
  // C is accurate to about the solver tolerance: classify with a margin above it
  res.symmetry_tol = std::max(1e-6, 10 * opt_.tol);
  res.symmetry = materials::classify(res.C, res.symmetry_tol);
  res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

} // namespace lamina::homogenize
