#include "homogenize/nonlinear_homogenizer.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "homogenize/conjugate_gradients.hpp"
#include "homogenize/fft.hpp"
#include "homogenize/field_operator.hpp"
#include "homogenize/green_operator.hpp"
#include "homogenize/homogenizer.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

namespace lamina::homogenize {

using materials::Matrix6;
using materials::Vector6;

namespace {

double dot(const double* a, const double* b, std::size_t n) {
  double s = 0;
#pragma omp parallel for reduction(+ : s) schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    s += a[i] * b[i];
  return s;
}

/// @return a field of @p n zeros
AlignedBuffer zeros(std::size_t n) {
  AlignedBuffer b(n);
  std::memset(b.data(), 0, n * sizeof(double));
  return b;
}

/// What is set up once and only read afterwards: the grid, its phases and
/// laws, the settings and threads, the gradient, the reference medium and
/// its Green operator (the preconditioner), and where the per-voxel state
/// of the nonlinear voxels lives.
struct CellSetup {
  Grid grid;
  std::vector<std::int32_t> phase;
  std::vector<materials::LawPtr> laws;
  NonlinearOptions opt;
  std::size_t N;
  SolverThreads threads;
  FieldOperator D;
  Matrix6 C0;
  double lambda0 = 0, mu0 = 0;    // the reference medium of C0
  std::vector<Matrix6> Cphase;    // elastic C of every phase (used for the linear ones)
  std::vector<std::int64_t> slot; // per voxel: index among nonlinear voxels, -1 if linear
  std::size_t nonlinear = 0;      // voxels with a nonlinear law
  std::size_t stride = 0;         // state doubles per nonlinear voxel
  std::unique_ptr<Distribution> dist;
  std::unique_ptr<VectorFft> fft;
  std::unique_ptr<GreenOperator> green;

  CellSetup(const Grid& g, std::vector<std::int32_t> ph, std::vector<materials::LawPtr> l,
            NonlinearOptions o)
      : grid(g), phase(std::move(ph)), laws(std::move(l)), opt(o), N(g.size()),
        threads(o.threads, N), D(g) {
    LAMINA_CHECK(phase.size() == N, "phase map size does not match the grid");
    LAMINA_CHECK(opt.tol > 0 && opt.eta > 0 && opt.eta < 1, "tolerances must be positive");
    referenceAndPhases();
    slot.assign(N, -1);
    for (std::size_t v = 0; v < N; ++v)
      if (!laws[static_cast<std::size_t>(phase[v])]->isLinear())
        slot[v] = static_cast<std::int64_t>(nonlinear++);
    const auto guard = threads.guard();
    const bool measure = opt.measure > 0 || (opt.measure < 0 && N > (1u << 18));
    dist = std::make_unique<Distribution>(Distribution::serial(grid));
    fft = std::make_unique<VectorFft>(grid, *dist, threads.count(), measure, Precision::Double);
    green = std::make_unique<GreenOperator>(grid, lambda0, mu0, *fft, *dist);
  }

  /// Checks the phase map against the laws; sets Cphase, stride and the
  /// reference medium of the phases present.
  void referenceAndPhases() {
    std::vector<std::size_t> count(laws.size(), 0);
    for (std::int32_t p : phase) {
      LAMINA_CHECK(p >= 0 && static_cast<std::size_t>(p) < laws.size(), "phase index ", p,
                   " has no law");
      ++count[static_cast<std::size_t>(p)];
    }
    std::vector<materials::Stiffness> present;
    for (std::size_t q = 0; q < laws.size(); ++q) {
      LAMINA_CHECK(laws[q] != nullptr, "phase ", q, " has no law");
      Cphase.push_back(laws[q]->elasticStiffness(1.0).matrix());
      if (!laws[q]->isLinear())
        stride = std::max(stride, static_cast<std::size_t>(laws[q]->stateSize()));
      if (count[q] > 0)
        present.push_back(laws[q]->elasticStiffness(1.0));
    }
    referenceMedium(present, lambda0, mu0);
    C0 = materials::Stiffness::fromLame(lambda0, mu0).matrix();
  }

  const Matrix6& phaseC(std::size_t v) const { return Cphase[static_cast<std::size_t>(phase[v])]; }
};

/// What a load step changes: the trial fields of the step being solved, and
/// the fields committed at the end of the last step with its increment (the
/// predictor of the next).
struct CellState {
  // trial: the Newton iterate of the current step
  AlignedBuffer u;                    // displacement (3 x N)
  Vector6 E = Vector6::Zero();        // macroscopic strain
  std::vector<double> eps, sig;       // voxel strains and stresses (6 x N)
  std::vector<double> state, tangent; // per nonlinear voxel: law state, symmetrized tangent
  // committed: the end of the last step
  AlignedBuffer u_c, du_last;
  Vector6 E_c = Vector6::Zero(), dE_last = Vector6::Zero();
  std::vector<double> eps_n, state_n;
  double t = 0, dt_last = 0;
  int steps_done = 0;

  explicit CellState(const CellSetup& s)
      : u(zeros(3 * s.N)), eps(6 * s.N, 0.0), sig(6 * s.N, 0.0),
        tangent(s.nonlinear * 36, 0.0), u_c(zeros(3 * s.N)), du_last(zeros(3 * s.N)),
        eps_n(6 * s.N, 0.0), state_n(s.nonlinear * s.stride, 0.0) {
    for (std::size_t v = 0; v < s.N; ++v)
      if (s.slot[v] >= 0)
        s.laws[static_cast<std::size_t>(s.phase[v])]->initState(&state_n[s.slot[v] * s.stride]);
    state = state_n;
  }

  /// Stress (and tangent) of every voxel at strain eps over dt from the
  /// committed state; returns the average stress.
  Vector6 evaluate(const CellSetup& s, double dt, bool with_tangent) {
    const std::size_t N = s.N;
    Vector6 total = Vector6::Zero();
    core::ParallelErrors errors; // a law refusing a state throws
#pragma omp parallel
    {
      Vector6 acc = Vector6::Zero();
#pragma omp for schedule(dynamic, 4096)
      for (std::size_t v = 0; v < N; ++v)
        errors.run([&] { acc += evaluateVoxel(s, v, dt, with_tangent); });
#pragma omp critical(lamina_nonlinear_evaluate)
      total += acc;
    }
    errors.rethrow();
    return total / static_cast<double>(N);
  }

  /// The stress of voxel @p v (stored into sig), and its tangent when asked.
  Vector6 evaluateVoxel(const CellSetup& s, std::size_t v, double dt, bool with_tangent) {
    const std::size_t N = s.N;
    Vector6 e, sv;
    for (int a = 0; a < 6; ++a)
      e[a] = eps[a * N + v];
    const std::int64_t k = s.slot[v];
    if (k < 0) {
      sv = s.phaseC(v) * e;
    } else {
      materials::PointStep step;
      for (int a = 0; a < 6; ++a)
        step.eps_n[a] = eps_n[a * N + v];
      step.eps = e;
      step.J_n = 1 + step.eps_n.head<3>().sum();
      step.J = 1 + e.head<3>().sum();
      step.dt = dt;
      Matrix6 T;
      s.laws[static_cast<std::size_t>(s.phase[v])]->update(
          step, &state_n[k * s.stride], &state[k * s.stride], sv, with_tangent ? &T : nullptr);
      if (with_tangent) {
        Eigen::Map<Matrix6> Tv(&tangent[static_cast<std::size_t>(k) * 36]);
        Tv = 0.5 * (T + T.transpose());
      }
    }
    for (int a = 0; a < 6; ++a)
      sig[a * N + v] = sv[a];
    return sv;
  }

  /// The predictor of a step over @p dt: the last increment scaled to it
  /// for u and the stress-controlled strains, the target for the others.
  void predict(double dt, const MacroStep& target, const std::array<bool, 6>& sc) {
    const std::size_t n = u.size();
    const double ratio = dt_last > 0 ? dt / dt_last : 0.0;
    double* up = u.data();
    const double* uc = u_c.data();
    const double* dl = du_last.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      up[i] = uc[i] + ratio * dl[i];
    for (int a = 0; a < 6; ++a)
      E[a] = sc[static_cast<std::size_t>(a)] ? E_c[a] + ratio * dE_last[a]
                                             : target.value[static_cast<std::size_t>(a)];
  }

  /// Makes the trial fields of a step over @p dt ending at @p t_end the
  /// committed ones.
  void commit(double dt, double t_end) {
    state_n.swap(state);
    eps_n = eps;
    const std::size_t n = u.size();
    double* dl = du_last.data();
    double* uc = u_c.data();
    const double* up = u.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      dl[i] = up[i] - uc[i];
      uc[i] = up[i];
    }
    dE_last = E - E_c;
    E_c = E;
    dt_last = dt;
    t = t_end;
    ++steps_done;
  }
};

/// The Newton system [D^T C_t D, D^T C_t P; P^T C_t D, P^T C_t P] (x, xE) =
/// (r, rE) for conjugate gradients, preconditioned by blockdiag(K0^+,
/// (N P^T C0 P)^-1) on the stress-controlled components sc. The caller sets
/// r, rE and sc; a solve leaves the solution in x, xE (r, rE are used up).
class NewtonSystem final : public CgProblem {
public:
  AlignedBuffer r, x;     // u-parts of the right-hand side and the solution
  Vector6 rE, xE;         // E-parts
  std::array<bool, 6> sc{}; // the stress-controlled components

  NewtonSystem(const CellSetup& setup, const std::vector<double>& tangent)
      : r(zeros(3 * setup.N)), x(zeros(3 * setup.N)), s_(setup), tangent_(tangent),
        tmp6_(6 * setup.N, 0.0), z_(zeros(3 * setup.N)), p_(zeros(3 * setup.N)),
        w_(zeros(3 * setup.N)) {}

  /// y = A (pu, pE): the tangent operator of the Newton system. Returns the
  /// E-part (sum over voxels of the stress of the strain P pE + D pu).
  Vector6 apply(const double* pu, const Vector6& pE, double* yu) {
    const std::size_t N = s_.N;
    std::array<double, 6> Ep{};
    for (int a = 0; a < 6; ++a)
      Ep[static_cast<std::size_t>(a)] = pE[a];
    s_.D.strain(pu, Ep, tmp6_.data());
    Vector6 total = Vector6::Zero();
#pragma omp parallel
    {
      Vector6 acc = Vector6::Zero();
#pragma omp for schedule(static)
      for (std::size_t v = 0; v < N; ++v) {
        Vector6 e;
        for (int a = 0; a < 6; ++a)
          e[a] = tmp6_[a * N + v];
        const std::int64_t k = s_.slot[v];
        const Vector6 sv = k < 0 ? Vector6(s_.phaseC(v) * e)
                                 : Vector6(Eigen::Map<const Matrix6>(&tangent_[k * 36]) * e);
        for (int a = 0; a < 6; ++a)
          tmp6_[a * N + v] = sv[a];
        acc += sv;
      }
#pragma omp critical(lamina_nonlinear_apply)
      total += acc;
    }
    s_.D.divergence(tmp6_.data(), yu);
    return total;
  }

  /// The E-part of A (pu, pE) alone (the u-part goes to scratch).
  Vector6 stressSum(const double* pu, const Vector6& pE) { return apply(pu, pE, w_.data()); }

  /// sqrt(r^T M r) of the right-hand side (r, rE).
  double norm() { return std::sqrt(std::max(precondition(), 0.0)); }

  double start() override {
    const std::size_t n = 3 * s_.N;
    std::memset(x.data(), 0, n * sizeof(double));
    xE.setZero();
    const double rz = precondition();
    std::memcpy(p_.data(), z_.data(), n * sizeof(double));
    pE_ = zE_;
    return rz;
  }

  double applyToDirection() override {
    wE_ = apply(p_.data(), pE_, w_.data());
    for (int a = 0; a < 6; ++a)
      if (!sc[static_cast<std::size_t>(a)])
        wE_[a] = 0;
    return dot(p_.data(), w_.data(), 3 * s_.N) + pE_.dot(wE_);
  }

  double update(double alpha, double rz, double rz_stop) override {
    const std::size_t n = 3 * s_.N;
    double* xp = x.data();
    double* rp = r.data();
    const double* pp = p_.data();
    const double* wp = w_.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      xp[i] += alpha * pp[i];
      rp[i] -= alpha * wp[i];
    }
    xE += alpha * pE_;
    rE -= alpha * wE_;
    const double rz_new = precondition();
    if (!(rz_new > rz_stop)) // converged (or NaN: the loop throws): p is not used again
      return rz_new;
    const double beta = rz_new / rz;
    double* pq = p_.data();
    const double* zp = z_.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      pq[i] = zp[i] + beta * pq[i];
    pE_ = zE_ + beta * pE_;
    return rz_new;
  }

  const char* indefiniteCause() const override {
    return "a tangent that is not positive definite";
  }

private:
  /// z = K0^+ r, zE = (N P^T C0 P)^-1 rE on sc. Returns r^T z.
  double precondition() {
    double rz = s_.green->apply(r.data(), z_.data());
    zE_.setZero();
    std::vector<int> f;
    for (int a = 0; a < 6; ++a)
      if (sc[static_cast<std::size_t>(a)])
        f.push_back(a);
    if (f.empty())
      return rz;
    const int m = static_cast<int>(f.size());
    Eigen::MatrixXd Cff(m, m);
    Eigen::VectorXd rf(m);
    for (int i = 0; i < m; ++i) {
      rf[i] = rE[f[static_cast<std::size_t>(i)]];
      for (int j = 0; j < m; ++j)
        Cff(i, j) = static_cast<double>(s_.N) *
                    s_.C0(f[static_cast<std::size_t>(i)], f[static_cast<std::size_t>(j)]);
    }
    const Eigen::VectorXd zf = Cff.llt().solve(rf);
    for (int i = 0; i < m; ++i)
      zE_[f[static_cast<std::size_t>(i)]] = zf[i];
    rz += rf.dot(zf);
    return rz;
  }

  const CellSetup& s_;
  const std::vector<double>& tangent_; // CellState::tangent
  std::vector<double> tmp6_;           // strains, then stresses, of apply()
  AlignedBuffer z_, p_, w_;
  Vector6 zE_, pE_, wE_;
};

} // namespace

/// The nonlinear cell: its setup (read only), the state a step changes,
/// and the Newton system's CG vectors (scratch of each solve).
struct NonlinearHomogenizer::Impl {
  const CellSetup setup;
  CellState cell;
  NewtonSystem system;

  Impl(const Grid& g, std::vector<std::int32_t> ph, std::vector<materials::LawPtr> l,
       NonlinearOptions o)
      : setup(g, std::move(ph), std::move(l), o), cell(setup), system(setup, cell.tangent) {}

  /// Newton residual into the system: r = -D^T sigma, rE = N Sigma_f - sum
  /// sigma_f. Returns sqrt(r^T M r).
  double residual(const Vector6& avg, const MacroStep& target) {
    const std::size_t N = setup.N;
    setup.D.divergence(cell.sig.data(), system.r.data());
    double* rp = system.r.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < 3 * N; ++i)
      rp[i] = -rp[i];
    system.rE.setZero();
    for (int a = 0; a < 6; ++a)
      if (system.sc[static_cast<std::size_t>(a)])
        system.rE[a] =
            static_cast<double>(N) * (target.value[static_cast<std::size_t>(a)] - avg[a]);
    return system.norm();
  }

  StepResult step(const MacroStep& target, const std::array<bool, 6>& sc) {
    const auto t0 = std::chrono::steady_clock::now();
    const double dt = target.t - cell.t;
    LAMINA_CHECK(dt >= 0, "load step times must not decrease");
    cell.predict(dt, target, sc);
    system.sc = sc;
    StepResult res;
    res.step = cell.steps_done + 1;
    res.t = target.t;
    newton(dt, target, res);
    cell.commit(dt, target.t);
    res.E = cell.E;
    phaseAverages(res);
    res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
  }

  /// Newton's iterations of a step over @p dt from the predictor to the
  /// converged trial fields; fills residual, Sigma, newton and krylov.
  void newton(double dt, const MacroStep& target, StepResult& res) {
    const NonlinearOptions& opt = setup.opt;
    const std::size_t n = 3 * setup.N;
    for (;;) {
      std::array<double, 6> Ea{};
      for (int a = 0; a < 6; ++a)
        Ea[static_cast<std::size_t>(a)] = cell.E[a];
      setup.D.strain(cell.u.data(), Ea, cell.eps.data());
      const Vector6 avg = cell.evaluate(setup, dt, true);
      const double rnorm = residual(avg, target);
      const Matrix6& C0 = setup.C0;
      const double energy = std::max(cell.E.dot(C0 * cell.E), 1e-12 * C0(3, 3));
      const double scale = std::sqrt(static_cast<double>(setup.N) * energy);
      res.residual = rnorm / scale;
      res.Sigma = avg;
      if (res.residual <= opt.tol)
        return;
      if (res.newton >= opt.max_newton) {
        std::ostringstream os;
        os << "Newton did not converge in " << opt.max_newton << " iterations at step " << res.step
           << " (residual " << res.residual << ")";
        throw Error(os.str());
      }
      const double stop = std::max(opt.eta * rnorm, 0.5 * opt.tol * scale);
      res.krylov += conjugateGradients(system, CgControl::absolute(stop, scale * scale,
                                                                   opt.max_krylov))
                        .iterations;
      double* up = cell.u.data();
      const double* xp = system.x.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        up[i] += xp[i];
      cell.E += system.xE;
      ++res.newton;
    }
  }

  void phaseAverages(StepResult& res) const {
    const std::size_t P = setup.laws.size(), N = setup.N;
    res.phase_E.assign(P, Vector6::Zero());
    res.phase_S.assign(P, Vector6::Zero());
    std::vector<std::size_t> count(P, 0);
    for (std::size_t v = 0; v < N; ++v) {
      const auto q = static_cast<std::size_t>(setup.phase[v]);
      ++count[q];
      for (int a = 0; a < 6; ++a) {
        res.phase_E[q][a] += cell.eps_n[a * N + v];
        res.phase_S[q][a] += cell.sig[a * N + v];
      }
    }
    for (std::size_t q = 0; q < P; ++q)
      if (count[q] > 0) {
        res.phase_E[q] /= static_cast<double>(count[q]);
        res.phase_S[q] /= static_cast<double>(count[q]);
      }
  }

  Matrix6 effectiveTangent(double dt) {
    const std::size_t N = setup.N;
    // tangents of a zero increment over dt from the committed state
    cell.eps = cell.eps_n;
    cell.evaluate(setup, dt, true);
    Matrix6 C = Matrix6::Zero();
    system.sc = {};
    for (int k = 0; k < 6; ++k) {
      Vector6 Ek = Vector6::Zero();
      Ek[k] = 1;
      // r = -D^T C_t E_k
      system.apply(nullptr, Ek, system.r.data());
      double* rp = system.r.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < 3 * N; ++i)
        rp[i] = -rp[i];
      system.rE = Vector6::Zero();
      const double scale = std::sqrt(static_cast<double>(N) * setup.C0(k, k));
      conjugateGradients(system,
                         CgControl::absolute(setup.opt.tol * scale, scale * scale,
                                             setup.opt.max_krylov));
      C.col(k) = system.stressSum(system.x.data(), Ek) / static_cast<double>(N);
    }
    return C;
  }
};

NonlinearHomogenizer::NonlinearHomogenizer(const Grid& grid, std::vector<std::int32_t> phase,
                                           std::vector<materials::LawPtr> laws,
                                           NonlinearOptions options)
    : impl_(std::make_unique<Impl>(grid, std::move(phase), std::move(laws), options)) {}

NonlinearHomogenizer::~NonlinearHomogenizer() = default;

std::vector<StepResult>
NonlinearHomogenizer::run(const MacroHistory& history,
                          const std::function<void(const StepResult&)>& report) {
  const auto guard = impl_->setup.threads.guard();
  std::vector<StepResult> out;
  for (const MacroStep& s : history.steps) {
    StepResult r;
    try {
      r = impl_->step(s, history.stress_controlled);
    } catch (const DivergenceError& e) {
      throw DivergenceError("load step " + std::to_string(impl_->cell.steps_done + 1) + ": " +
                            e.message());
    }
    if (report)
      report(r);
    out.push_back(std::move(r));
  }
  return out;
}

Matrix6 NonlinearHomogenizer::effectiveTangent(double dt) {
  const auto guard = impl_->setup.threads.guard();
  return impl_->effectiveTangent(dt);
}

const std::vector<double>& NonlinearHomogenizer::strainField() const {
  return impl_->cell.eps_n;
}
const std::vector<double>& NonlinearHomogenizer::stressField() const {
  return impl_->cell.sig;
}
const Grid& NonlinearHomogenizer::grid() const {
  return impl_->setup.grid;
}

} // namespace lamina::homogenize
