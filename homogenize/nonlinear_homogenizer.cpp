#include "homogenize/nonlinear_homogenizer.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"
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

} // namespace

struct NonlinearHomogenizer::Impl {
  Grid grid;
  std::vector<std::int32_t> phase;
  std::vector<materials::LawPtr> laws;
  NonlinearOptions opt;
  std::size_t N;
  int threads;
  FieldOperator D;
  std::unique_ptr<Distribution> dist;
  std::unique_ptr<VectorFft> fft;
  std::unique_ptr<GreenOperator> green;
  Matrix6 C0;
  std::vector<Matrix6> Cphase;    // elastic C of linear phases
  std::vector<std::int64_t> slot; // per voxel: index among nonlinear voxels, -1 if linear
  std::size_t stride = 0;         // state doubles per nonlinear voxel
  std::vector<double> state_n, state, tangent;
  std::vector<double> eps_n, eps, sig, tmp6;
  AlignedBuffer u, u_c, du_last, r, z, p, w, x;
  Vector6 E = Vector6::Zero(), E_c = Vector6::Zero(), dE_last = Vector6::Zero();
  double t = 0, dt_last = 0;
  int steps_done = 0;

  Impl(const Grid& g, std::vector<std::int32_t> ph, std::vector<materials::LawPtr> l,
       NonlinearOptions o)
      : grid(g), phase(std::move(ph)), laws(std::move(l)), opt(o), N(g.size()),
        threads(solverThreads(o.threads, N)),
        D(g) {
    LAMINA_CHECK(phase.size() == N, "phase map size does not match the grid");
    LAMINA_CHECK(opt.tol > 0 && opt.eta > 0 && opt.eta < 1, "tolerances must be positive");
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
    double lambda0 = 0, mu0 = 0;
    referenceMedium(present, lambda0, mu0);
    C0 = materials::Stiffness::fromLame(lambda0, mu0).matrix();
    slot.assign(N, -1);
    std::size_t n_nl = 0;
    for (std::size_t v = 0; v < N; ++v)
      if (!laws[static_cast<std::size_t>(phase[v])]->isLinear())
        slot[v] = static_cast<std::int64_t>(n_nl++);
    state_n.assign(n_nl * stride, 0.0);
    tangent.assign(n_nl * 36, 0.0);
    for (std::size_t v = 0; v < N; ++v)
      if (slot[v] >= 0)
        laws[static_cast<std::size_t>(phase[v])]->initState(&state_n[slot[v] * stride]);
    state = state_n;
    eps_n.assign(6 * N, 0.0);
    eps.assign(6 * N, 0.0);
    sig.assign(6 * N, 0.0);
    tmp6.assign(6 * N, 0.0);
    for (AlignedBuffer* b : {&u, &u_c, &du_last, &r, &z, &p, &w, &x}) {
      *b = AlignedBuffer(3 * N);
      std::memset(b->data(), 0, 3 * N * sizeof(double));
    }
    core::ThreadsScope scope(threads);
    const bool measure = opt.measure > 0 || (opt.measure < 0 && N > (1u << 18));
    dist = std::make_unique<Distribution>(Distribution::serial(grid));
    fft = std::make_unique<VectorFft>(grid, *dist, threads, measure, Precision::Double);
    green = std::make_unique<GreenOperator>(grid, lambda0, mu0, *fft, *dist);
  }

  const Matrix6& phaseC(std::size_t v) const { return Cphase[static_cast<std::size_t>(phase[v])]; }

  /// Stress (and tangent) of every voxel at strain eps over dt from the
  /// committed state; returns the average stress.
  Vector6 evaluate(double dt, bool with_tangent) {
    Vector6 total = Vector6::Zero();
    core::ParallelErrors errors; // a law refusing a state throws
#pragma omp parallel
    {
      Vector6 acc = Vector6::Zero();
#pragma omp for schedule(dynamic, 4096)
      for (std::size_t v = 0; v < N; ++v)
        errors.run([&] {
          Vector6 e, s;
          for (int a = 0; a < 6; ++a)
            e[a] = eps[a * N + v];
          const std::int64_t k = slot[v];
          if (k < 0) {
            s = phaseC(v) * e;
          } else {
            materials::PointStep step;
            for (int a = 0; a < 6; ++a)
              step.eps_n[a] = eps_n[a * N + v];
            step.eps = e;
            step.J_n = 1 + step.eps_n.head<3>().sum();
            step.J = 1 + e.head<3>().sum();
            step.dt = dt;
            Matrix6 T;
            laws[static_cast<std::size_t>(phase[v])]->update(
                step, &state_n[k * stride], &state[k * stride], s, with_tangent ? &T : nullptr);
            if (with_tangent) {
              Eigen::Map<Matrix6> Tv(&tangent[static_cast<std::size_t>(k) * 36]);
              Tv = 0.5 * (T + T.transpose());
            }
          }
          for (int a = 0; a < 6; ++a)
            sig[a * N + v] = s[a];
          acc += s;
        });
#pragma omp critical(lamina_nonlinear_evaluate)
      total += acc;
    }
    errors.rethrow();
    return total / static_cast<double>(N);
  }

  /// y = A (pu, pE): the tangent operator of the Newton system. Returns the
  /// E-part (sum over voxels of the stress of the strain P pE + D pu).
  Vector6 apply(const double* pu, const Vector6& pE, double* yu) {
    std::array<double, 6> Ep{};
    for (int a = 0; a < 6; ++a)
      Ep[static_cast<std::size_t>(a)] = pE[a];
    D.strain(pu, Ep, tmp6.data());
    Vector6 total = Vector6::Zero();
#pragma omp parallel
    {
      Vector6 acc = Vector6::Zero();
#pragma omp for schedule(static)
      for (std::size_t v = 0; v < N; ++v) {
        Vector6 e;
        for (int a = 0; a < 6; ++a)
          e[a] = tmp6[a * N + v];
        const std::int64_t k = slot[v];
        const Vector6 s = k < 0 ? Vector6(phaseC(v) * e)
                                : Vector6(Eigen::Map<const Matrix6>(&tangent[k * 36]) * e);
        for (int a = 0; a < 6; ++a)
          tmp6[a * N + v] = s[a];
        acc += s;
      }
#pragma omp critical(lamina_nonlinear_apply)
      total += acc;
    }
    D.divergence(tmp6.data(), yu);
    return total;
  }

  /// Preconditioner: zu = K0^+ ru, zE = (N P^T C0 P)^-1 rE. Returns r^T z.
  double precondition(const double* ru, const Vector6& rE, const std::array<bool, 6>& sc,
                      double* zu, Vector6& zE) const {
    double rz = green->apply(ru, zu);
    zE.setZero();
    std::vector<int> f;
    for (int a = 0; a < 6; ++a)
      if (sc[static_cast<std::size_t>(a)])
        f.push_back(a);
    if (!f.empty()) {
      const int m = static_cast<int>(f.size());
      Eigen::MatrixXd Cff(m, m);
      Eigen::VectorXd rf(m);
      for (int i = 0; i < m; ++i) {
        rf[i] = rE[f[static_cast<std::size_t>(i)]];
        for (int j = 0; j < m; ++j)
          Cff(i, j) = static_cast<double>(N) *
                      C0(f[static_cast<std::size_t>(i)], f[static_cast<std::size_t>(j)]);
      }
      const Eigen::VectorXd zf = Cff.llt().solve(rf);
      for (int i = 0; i < m; ++i)
        zE[f[static_cast<std::size_t>(i)]] = zf[i];
      rz += rf.dot(zf);
    }
    return rz;
  }

  /// Preconditioned CG on A (x, xE) = (r, rE); r and rE are overwritten.
  /// Stops when sqrt(r^T M r) <= stop. Returns the iterations.
  int pcg(Vector6& rE, const std::array<bool, 6>& sc, double stop, Vector6& xE) {
    const std::size_t n = 3 * N;
    std::memset(x.data(), 0, n * sizeof(double));
    xE.setZero();
    Vector6 zE, pE, wE;
    double rz = precondition(r.data(), rE, sc, z.data(), zE);
    std::memcpy(p.data(), z.data(), n * sizeof(double));
    pE = zE;
    int it = 0;
    while (std::sqrt(std::max(rz, 0.0)) > stop) {
      if (it >= opt.max_krylov) {
        std::ostringstream os;
        os << "conjugate gradients did not converge in " << opt.max_krylov << " iterations";
        throw Error(os.str());
      }
      wE = apply(p.data(), pE, w.data());
      for (int a = 0; a < 6; ++a)
        if (!sc[static_cast<std::size_t>(a)])
          wE[a] = 0;
      const double pw = dot(p.data(), w.data(), n) + pE.dot(wE);
      if (!(pw > 0) || !std::isfinite(pw))
        throw DivergenceError("conjugate gradients broke down (p^T A p = " + std::to_string(pw) +
                              "): NaN/Inf or a tangent that is not positive definite");
      const double alpha = rz / pw;
      double* xp = x.data();
      double* rp = r.data();
      const double* pp = p.data();
      const double* wp = w.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        xp[i] += alpha * pp[i];
        rp[i] -= alpha * wp[i];
      }
      xE += alpha * pE;
      rE -= alpha * wE;
      const double rz_new = precondition(r.data(), rE, sc, z.data(), zE);
      if (!std::isfinite(rz_new))
        throw DivergenceError("residual is NaN/Inf in conjugate gradients");
      const double beta = rz_new / rz;
      rz = rz_new;
      double* pq = p.data();
      const double* zp = z.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        pq[i] = zp[i] + beta * pq[i];
      pE = zE + beta * pE;
      ++it;
    }
    return it;
  }

  /// Newton residual: r = -D^T sigma, rE = N Sigma_f - sum sigma_f. Returns
  /// sqrt(r^T M r) (M applied into z).
  double residual(const Vector6& avg, const MacroStep& target, const std::array<bool, 6>& sc,
                  Vector6& rE) {
    D.divergence(sig.data(), r.data());
    double* rp = r.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < 3 * N; ++i)
      rp[i] = -rp[i];
    rE.setZero();
    for (int a = 0; a < 6; ++a)
      if (sc[static_cast<std::size_t>(a)])
        rE[a] = static_cast<double>(N) * (target.value[static_cast<std::size_t>(a)] - avg[a]);
    Vector6 zE;
    return std::sqrt(std::max(precondition(r.data(), rE, sc, z.data(), zE), 0.0));
  }

  StepResult step(const MacroStep& target, const std::array<bool, 6>& sc) {
    const auto t0 = std::chrono::steady_clock::now();
    const double dt = target.t - t;
    LAMINA_CHECK(dt >= 0, "load step times must not decrease");
    const std::size_t n = 3 * N;
    // predictor: previous increment scaled to this step
    const double ratio = dt_last > 0 ? dt / dt_last : 0.0;
    {
      double* up = u.data();
      const double* uc = u_c.data();
      const double* dl = du_last.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        up[i] = uc[i] + ratio * dl[i];
    }
    for (int a = 0; a < 6; ++a)
      E[a] = sc[static_cast<std::size_t>(a)] ? E_c[a] + ratio * dE_last[a]
                                             : target.value[static_cast<std::size_t>(a)];
    StepResult res;
    res.step = steps_done + 1;
    res.t = target.t;
    for (;;) {
      std::array<double, 6> Ea{};
      for (int a = 0; a < 6; ++a)
        Ea[static_cast<std::size_t>(a)] = E[a];
      D.strain(u.data(), Ea, eps.data());
      const Vector6 avg = evaluate(dt, true);
      Vector6 rE;
      const double rnorm = residual(avg, target, sc, rE);
      const double energy = std::max(E.dot(C0 * E), 1e-12 * C0(3, 3));
      const double scale = std::sqrt(static_cast<double>(N) * energy);
      res.residual = rnorm / scale;
      res.Sigma = avg;
      if (res.residual <= opt.tol)
        break;
      if (res.newton >= opt.max_newton) {
        std::ostringstream os;
        os << "Newton did not converge in " << opt.max_newton << " iterations at step " << res.step
           << " (residual " << res.residual << ")";
        throw Error(os.str());
      }
      Vector6 xE;
      res.krylov += pcg(rE, sc, std::max(opt.eta * rnorm, 0.5 * opt.tol * scale), xE);
      double* up = u.data();
      const double* xp = x.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        up[i] += xp[i];
      E += xE;
      ++res.newton;
    }
    // commit
    state_n.swap(state);
    eps_n = eps;
    {
      double* dl = du_last.data();
      double* uc = u_c.data();
      const double* up = u.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        dl[i] = up[i] - uc[i];
        uc[i] = up[i];
      }
    }
    dE_last = E - E_c;
    E_c = E;
    dt_last = dt;
    t = target.t;
    ++steps_done;
    res.E = E;
    phaseAverages(res);
    res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
  }

  void phaseAverages(StepResult& res) const {
    const std::size_t P = laws.size();
    res.phase_E.assign(P, Vector6::Zero());
    res.phase_S.assign(P, Vector6::Zero());
    std::vector<std::size_t> count(P, 0);
    for (std::size_t v = 0; v < N; ++v) {
      const auto q = static_cast<std::size_t>(phase[v]);
      ++count[q];
      for (int a = 0; a < 6; ++a) {
        res.phase_E[q][a] += eps_n[a * N + v];
        res.phase_S[q][a] += sig[a * N + v];
      }
    }
    for (std::size_t q = 0; q < P; ++q)
      if (count[q] > 0) {
        res.phase_E[q] /= static_cast<double>(count[q]);
        res.phase_S[q] /= static_cast<double>(count[q]);
      }
  }

  Matrix6 effectiveTangent(double dt) {
    // tangents of a zero increment over dt from the committed state
    eps = eps_n;
    evaluate(dt, true);
    Matrix6 C = Matrix6::Zero();
    const std::array<bool, 6> none{};
    for (int k = 0; k < 6; ++k) {
      Vector6 Ek = Vector6::Zero();
      Ek[k] = 1;
      // r = -D^T C_t E_k
      apply(nullptr, Ek, r.data());
      double* rp = r.data();
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < 3 * N; ++i)
        rp[i] = -rp[i];
      Vector6 rE = Vector6::Zero(), xE;
      const double scale = std::sqrt(static_cast<double>(N) * C0(k, k));
      pcg(rE, none, opt.tol * scale, xE);
      C.col(k) = apply(x.data(), Ek, w.data()) / static_cast<double>(N);
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
  core::ThreadsScope scope(impl_->threads);
  std::vector<StepResult> out;
  for (const MacroStep& s : history.steps) {
    StepResult r;
    try {
      r = impl_->step(s, history.stress_controlled);
    } catch (const DivergenceError& e) {
      throw DivergenceError("load step " + std::to_string(impl_->steps_done + 1) + ": " +
                            e.message());
    }
    if (report)
      report(r);
    out.push_back(std::move(r));
  }
  return out;
}

Matrix6 NonlinearHomogenizer::effectiveTangent(double dt) {
  core::ThreadsScope scope(impl_->threads);
  return impl_->effectiveTangent(dt);
}

const std::vector<double>& NonlinearHomogenizer::strainField() const {
  return impl_->eps_n;
}
const std::vector<double>& NonlinearHomogenizer::stressField() const {
  return impl_->sig;
}
const Grid& NonlinearHomogenizer::grid() const {
  return impl_->grid;
}

} // namespace lamina::homogenize
