#include "homogenize/homogenizer.hpp"

#include "core/error.hpp"
#include "core/progress.hpp"
#include "homogenize/cell_operator.hpp"
#include "homogenize/fft.hpp"
#include "homogenize/green_operator.hpp"
#include "homogenize/start_residual.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
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

void referenceMedium(const std::vector<materials::Stiffness>& C, double& lambda0, double& mu0) {
  double kmin = std::numeric_limits<double>::max(), kmax = 0;
  double gmin = std::numeric_limits<double>::max(), gmax = 0;
  // one 6x6 inversion per phase (composite voxels: tens of thousands of
  // phases), on the threads; min and max do not depend on the order
  const long count = static_cast<long>(C.size());
#pragma omp parallel for schedule(static) reduction(min : kmin, gmin) reduction(max : kmax, gmax)
  for (long p = 0; p < count; ++p) {
    const auto& c = C[static_cast<std::size_t>(p)];
    double kr = 0, gr = 0;
    materials::reussModuli(c, kr, gr);
    kmin = std::min(kmin, kr);
    kmax = std::max(kmax, materials::voigtBulk(c));
    gmin = std::min(gmin, gr);
    gmax = std::max(gmax, materials::voigtShear(c));
  }
  const double K0 = std::sqrt(kmin * kmax);
  mu0 = std::sqrt(gmin * gmax);
  lambda0 = K0 - 2.0 * mu0 / 3.0;
}

Precision autoPrecision(double tol) {
  return tol >= 1e-6 ? Precision::Single : Precision::Double;
}

bool floatVectors(Precision fft, double tol) {
  return fft == Precision::Single && tol >= kFloatVectorsTol;
}

namespace {

/// The pieces of one solve, set up once and reused by the six load cases.
/// V: the type of the CG vectors and of the operator's arithmetic, float
/// when floatVectors() (single-precision transforms and tol >=
/// kFloatVectorsTol: the float rounding left in C is then at most of the
/// order of what the tolerance leaves), else double. The scalars (alpha, beta) and the sums over
/// the grid (p^T A p, r^T z, <C D p>, x^T r) stay double.
template <class V>
class CgSolver {
public:
  CgSolver(std::size_t local, const CellOperator& A, const StartResidual& b, const GreenOperator& M,
           const Distribution& dist, double ref_scale)
      : n_(3 * local), A_(A), b_(b), M_(M), dist_(dist), ref_(ref_scale), r_(n_), p_(n_), w_(n_) {}

  /// Solves load case E; returns the average stress in @p sigma and, if @p x
  /// is not null, the displacement (3 x local) in @p x.
  /// The average stress is linear in the displacement, <C (E + D x)> = <C E>
  /// + sum_k alpha_k <C D p_k>, and <C D p_k> comes out of the stress pass of
  /// A p_k, so x is formed only when asked for.
  LoadCaseResult solve(const std::array<double, 6>& E, double energy_E, const Options& opt,
                       const std::function<void(int, double)>& monitor,
                       std::array<double, 6>& sigma, V* x) {
    V* r = r_.data();
    V* p = p_.data();
    V* w = w_.data();
    const std::size_t n = n_;
    // r = b = -D^T C E (x = 0) and sigma = <C E>: the operator's values with
    // u = 0, formed only next to interfaces (start_residual.hpp)
    b_.apply(E, r, sigma);
    if (x) {
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        x[i] = 0;
    }
    double rz = M_.apply(r, p); // p0 = z0 = M r0, rz = r0^T z0
    const double scale = ref_ * energy_E;
    LoadCaseResult res;
    res.residual = std::sqrt(std::max(rz, 0.0) / scale);
    const std::array<double, 6> zero{0, 0, 0, 0, 0, 0};
    // converged when residual <= tol, i.e. r^T z <= tol^2 scale (the same
    // test decides in step() whether the last inverse transforms are needed)
    const double rz_stop = opt.tol * opt.tol * scale;
    while (rz > rz_stop) {
      if (res.iterations >= opt.max_iterations) {
        std::ostringstream os;
        os << "conjugate gradients did not reach tol " << opt.tol << " in " << opt.max_iterations
           << " iterations (residual " << res.residual << ")";
        throw Error(os.str());
      }
      double pw = 0;
      std::array<double, 6> sigma_p{};
      // w = A p; pw = p^T A p and <C D p> from the stress pass
      A_.apply(p, zero, w, &sigma_p, &pw);
      const double alpha = rz / pw;
      if (!std::isfinite(alpha) || !(pw > 0))
        throw DivergenceError("conjugate gradients broke down (p^T A p = " + std::to_string(pw) +
                              "): NaN/Inf or an indefinite phase stiffness");
      for (std::size_t a = 0; a < 6; ++a)
        sigma[a] += alpha * sigma_p[a];
      // r -= alpha w, x += alpha p, z = M r, p = z + beta p: fused passes
      // (the last step skips the inverse transforms: z would not be used)
      const double rz_new = M_.step(r, alpha, w, x, p, rz, rz_stop);
      if (!std::isfinite(rz_new))
        throw DivergenceError("residual is NaN/Inf in conjugate gradients");
      rz = rz_new;
      ++res.iterations;
      res.residual = std::sqrt(std::max(rz, 0.0) / scale);
      if (monitor)
        monitor(res.iterations, res.residual);
    }
    // With x formed, one stress pass gives <C (E + D x)> directly: the sum of
    // alpha_k <C D p_k> carries the rounding of every step's average (1e-12
    // relative at 128^3, enough to tell thread counts or ranks apart). With
    // single-precision transforms (tol >= 1e-6) that rounding is 5 decades
    // below what the tolerance leaves in C: the pass is skipped.
    if (x && res.iterations > 0 && std::is_same_v<V, double>)
      A_.apply(x, E, static_cast<V*>(nullptr), &sigma);
    return res;
  }

  /// dots[j] = x_j^T r (r: the last solve's final residual), j < count, summed
  /// over ranks, in one pass over r.
  void residualDots(const std::vector<AlignedArray<V>>& x, int count, double* dots) const {
    const V* r = r_.data();
    const V* xs[6] = {};
    for (int j = 0; j < count; ++j)
      xs[j] = x[static_cast<std::size_t>(j)].data();
    double d[6] = {0, 0, 0, 0, 0, 0};
#pragma omp parallel for schedule(static) reduction(+ : d[:6])
    for (std::size_t i = 0; i < n_; ++i)
      for (int j = 0; j < count; ++j)
        d[j] += static_cast<double>(xs[j][i]) * static_cast<double>(r[i]);
    for (int j = 0; j < count; ++j)
      dots[j] = d[j];
    dist_.sum(dots, count);
  }

private:
  std::size_t n_;
  const CellOperator& A_;
  const StartResidual& b_;
  const GreenOperator& M_;
  const Distribution& dist_;
  double ref_;
  AlignedArray<V> r_, p_, w_;
};

} // namespace

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
  // threads, the first invalid one again to throw its message
  const long phases = static_cast<long>(C_.size());
  long bad = phases;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (long p = 0; p < phases; ++p) {
    try {
      C_[static_cast<std::size_t>(p)].validate("");
    } catch (...) { // thrown again below, outside the region
      bad = std::min(bad, p);
    }
  }
  if (bad < phases)
    C_[static_cast<std::size_t>(bad)].validate("phase " + std::to_string(bad));
}

template <class V>
void Homogenizer::solveCases(const CellOperator& A, const StartResidual& b, const GreenOperator& M,
                             const materials::Stiffness& C0, Result& res, materials::Matrix6& C,
                             materials::Matrix6& C_energy) {
  CgSolver<V> cg(dist_.localSize(), A, b, M, dist_, static_cast<double>(res.voxels));
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
    auto monitor = [&](int it, double r) {
      if (monitor_)
        monitor_(k, it, r);
      else {
        std::ostringstream os;
        os << "load case " << k + 1 << "/6, iteration " << it << ", residual " << r;
        progress.update(k, os.str());
      }
    };
    try {
      V* xk = x.empty() ? nullptr : x[energy_form ? static_cast<std::size_t>(k) : 0].data();
      res.cases[static_cast<std::size_t>(k)] = cg.solve(E, energy, opt_, monitor, sigma, xk);
    } catch (const DivergenceError& e) {
      throw DivergenceError("load case " + std::to_string(k + 1) + ": " + e.message());
    } catch (const Error& e) {
      throw Error("load case " + std::to_string(k + 1) + ": " + e.message());
    }
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
  progress.finish();
}

Result Homogenizer::run() {
  const auto t0 = std::chrono::steady_clock::now();
  // Threads: as asked, or (auto) all for grids worth it. Below ~64k voxels a
  // CG iteration is too short to amortise the fork/join of its parallel
  // loops, and on shared cores a team can wait a scheduler slice per barrier.
  const int threads = opt_.threads > 0       ? opt_.threads
                      : grid_.size() < 65536 ? 1
                                             : omp_get_max_threads();
  struct ThreadsGuard {
    int saved = omp_get_max_threads();
    ~ThreadsGuard() { omp_set_num_threads(saved); }
  } guard;
  omp_set_num_threads(threads);
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
  VectorFft fft(grid_, dist_, threads, measure, res.precision);
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
