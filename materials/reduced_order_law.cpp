#include "materials/reduced_order_law.hpp"

#include "core/error.hpp"
#include "materials/gvbo_law.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace lamina::materials {

namespace {

using Eigen::Index;

Index idx(std::size_t k) {
  return static_cast<Index>(k);
}

std::size_t uz(int k) {
  return static_cast<std::size_t>(k);
}

double trace(const Vector6& e) {
  return e[0] + e[1] + e[2];
}

/// The volume ratio of a partition of strain trace @p tr_a in a coarse point
/// of volume ratio @p J and strain trace @p tr_c. Small kinematics (J = 1 +
/// tr eps, as the FFT cell and `materials drive --kinematics small` define
/// it): J_a = 1 + tr_a, exactly the full-field voxel's. Finite kinematics
/// (eps the integrated rate of deformation, so tr eps = ln J): J_a = J
/// exp(tr_a - tr_c), exact for that definition.
double partitionJ(double J, double tr_a, double tr_c) {
  if (std::abs(J - (1 + tr_c)) <= 1e-12 * std::max(1.0, std::abs(J)))
    return J + tr_a - tr_c;
  return J * std::exp(tr_a - tr_c);
}

} // namespace

/// The nonlinear partitions at trial strains: stresses, tangents,
/// eigenstrains and their laws' new states (a buffer apart from the state,
/// which may alias state_n until the step is accepted).
struct ReducedOrderLaw::Trial {
  std::vector<Vector6> eps, sigma, mu;
  std::vector<Matrix6> T;
  std::vector<double> state;
  explicit Trial(std::size_t m, int state_size)
      : eps(m), sigma(m), mu(m), T(m), state(uz(state_size)) {}
};

/// The reference medium of clustering and its interaction tensors
/// G^(beta alpha) = (Ga - beta0 Gb) / mu0 (n * n).
struct ReducedOrderLaw::Reference {
  Matrix6 C0;
  std::vector<Matrix6> G;
  Reference(const ReducedOrderModel& m, const std::array<double, 2>& lame) {
    const double lambda0 = lame[0], mu0 = lame[1];
    C0 = Stiffness::fromLame(lambda0, mu0).matrix();
    const double b = (lambda0 + mu0) / (lambda0 + 2 * mu0);
    G.resize(m.Ga.size());
    for (std::size_t k = 0; k < G.size(); ++k)
      G[k] = (m.Ga[k] - b * m.Gb[k]) / mu0;
  }
};

namespace {

/// the reference shear modulus of clustering stays above this fraction of
/// the one at rest: a phase in steady flow has a secant that keeps falling,
/// and Gamma0 ~ 1 / mu0
constexpr double kShearFloor = 1e-3;

/// clustering: the Newton residual is measured against strains of at least
/// this (ReducedOrderLaw::residual)
constexpr double kStrainFloor = 1e-14;

/// @return the shear modulus of the isotropic part of a 6x6 stiffness
/// (lamina order, engineering shear): 2 mu = (C_ijij - C_iijj / 3) / 5
double isotropicShear(const Matrix6& C) {
  const double iijj = C.topLeftCorner<3, 3>().sum();
  const double ijij = C.diagonal().head<3>().sum() + 2 * C.diagonal().tail<3>().sum();
  return (ijij - iijj / 3) / 10;
}

/// @return the bulk modulus of the isotropic part of @p C: 3 kappa = C_iijj / 3
double bulkOf(const Matrix6& C) {
  return C.topLeftCorner<3, 3>().sum() / 9;
}

/// @return the secant shear modulus (dev s : dev e) / (2 dev e : dev e) of
/// stress @p s and strain @p e (engineering shear; tensor contractions), or
/// 0 when |dev e| is at most @p small
double secantShear(const Vector6& s, const Vector6& e, double small) {
  const double ms = trace(s) / 3, me = trace(e) / 3;
  double se = 0, ee = 0;
  for (int i = 0; i < 3; ++i) {
    se += (s[i] - ms) * (e[i] - me);
    ee += (e[i] - me) * (e[i] - me);
  }
  for (int i = 3; i < 6; ++i) { // the tensor shear gamma / 2 appears twice
    se += s[i] * e[i];
    ee += 0.5 * e[i] * e[i];
  }
  if (!(std::sqrt(ee) > small))
    return 0;
  return se / (2 * ee);
}

} // namespace

ReducedOrderLaw::ReducedOrderLaw(std::string entry, ReducedOrderModel model,
                                 ReducedOrderOptions options)
    : entry_(std::move(entry)), model_(std::move(model)), options_(options) {
  try {
    model_.validate("reduced-order cell");
    LAMINA_CHECK(options_.tolerance > 0 && std::isfinite(options_.tolerance),
                 "the Newton tolerance must be positive, got ", options_.tolerance);
    LAMINA_CHECK(options_.max_iterations >= 1, "the Newton cap must be at least 1 iteration");
    std::vector<LawPtr> phase_laws;
    for (const ReducedOrderPhase& ph : model_.phases)
      phase_laws.push_back(ph.law.make()); // refuses a reduced-order phase
    const int n = model_.partitions();
    for (int a = 0; a < n; ++a) {
      laws_.push_back(phase_laws[uz(model_.partition_phase[uz(a)])]);
      L0_.push_back(laws_.back()->elasticStiffness(1.0).matrix());
      L0inv_.push_back(L0_.back().inverse());
      LAMINA_CHECK(L0inv_.back().allFinite(), "the reference stiffness of partition ", a,
                   " is singular");
      (laws_.back()->isLinear() ? linear_ : nonlinear_).push_back(a);
    }
    checkPhasesMatchArrays();
  } catch (const Error& e) {
    fail(e.message());
  }
  const int n = model_.partitions();
  clustering_ = model_.scheme == ReducedOrderScheme::Clustering;
  if (clustering_)
    for (int a = 0; a < n; ++a)
      unknown_.push_back(a);
  else
    unknown_ = nonlinear_;
  for (std::size_t k = 0; k < nonlinear_.size(); ++k)
    nl_slot_.push_back(clustering_ ? nonlinear_[k] : static_cast<int>(k));
  offset_.assign(uz(n), -1);
  if (!nonlinear_.empty()) {
    for (int a = 0; a < n; ++a) {
      offset_[uz(a)] = state_size_;
      state_size_ += 6 + laws_[uz(a)]->stateSize();
    }
    if (clustering_) {
      reference_offset_ = state_size_;
      state_size_ += 1; // the reference shear modulus mu0
    }
  }
  for (int a : unknown_) {
    trial_offset_.push_back(trial_state_size_);
    trial_state_size_ += laws_[uz(a)]->isLinear() ? 0 : laws_[uz(a)]->stateSize();
  }
  prepareCoupling();
}

void ReducedOrderLaw::prepareCoupling() {
  const int n = model_.partitions();
  const std::size_t m = nonlinear_.size();
  C_linear_.setZero();
  B_.assign(clustering_ ? 0 : m, Matrix6::Zero());
  if (clustering_) {
    // the reference medium at rest (J = 1): the softest phase's shear
    // modulus, the bulk modulus of the cell it gives, converged far below
    // any use
    mu_rest_ = softestShear(L0_);
    kappa0_ = bulkOf(model_.C);
    for (int solve = 0; solve < 200; ++solve) {
      const double fit = bulkOf(referenceTangent(L0_, mu_rest_));
      if (!(std::isfinite(fit) && fit > 0))
        break;
      const bool held = std::abs(fit - kappa0_) <= 1e-12 * kappa0_;
      kappa0_ = fit;
      if (held)
        break;
    }
    if (nonlinear_.empty()) // a linear cell: its stiffness in the converged medium
      C_linear_ = referenceTangent(L0_, mu_rest_);
  } else {
    for (int e : linear_)
      C_linear_ += model_.fraction[uz(e)] * L0_[uz(e)] * model_.A[uz(e)];
    for (std::size_t k = 0; k < m; ++k)
      for (int e : linear_)
        B_[k] += model_.fraction[uz(e)] * L0_[uz(e)] * model_.P[uz(e * n + nonlinear_[k])];
  }
  R_nl_.resize(6 * idx(m), 6 * idx(m));
  Q_nl_.resize(6, 6 * idx(m));
  for (std::size_t k = 0; k < m; ++k) {
    const int a = nonlinear_[k];
    for (std::size_t l = 0; l < m; ++l)
      R_nl_.block<6, 6>(6 * idx(k), 6 * idx(l)) = model_.R.block<6, 6>(6 * a, 6 * nonlinear_[l]);
    Q_nl_.block<6, 6>(0, 6 * idx(k)) = model_.Q.block<6, 6>(0, 6 * a);
  }
}

void ReducedOrderLaw::checkPhasesMatchArrays() const {
  // The side file's C was formed as sym(sum c L0 A) with the phases' L0 at
  // build time: phases edited, swapped or reordered since then no longer
  // match A and P. Its rounding is ~1e-15 of max|C|: 1e-9 leaves room.
  std::vector<Stiffness> L0(model_.phases.size());
  for (std::size_t a = 0; a < laws_.size(); ++a)
    L0[uz(model_.partition_phase[a])] = Stiffness(L0_[a]);
  const Matrix6 C = model_.referenceStiffness(L0);
  const double scale = model_.C.cwiseAbs().maxCoeff();
  const double diff = (C - model_.C).cwiseAbs().maxCoeff();
  if (!(diff <= 1e-9 * scale))
    fail(detail::concat("the phases' laws do not match the side file's arrays (sum c L0 A "
                        "differs from its C by ",
                        diff / scale, " of max|C|): were the phases edited or reordered?"));
}

void ReducedOrderLaw::fail(const std::string& message) const {
  throw Error("reduced-order cell: " + message, {"", 0, entry_});
}

void ReducedOrderLaw::initState(double* state) const {
  for (std::size_t a = 0; a < offset_.size(); ++a) {
    if (offset_[a] < 0)
      continue; // a linear cell has no state
    std::fill(state + offset_[a], state + offset_[a] + 6, 0.0);
    laws_[a]->initState(state + offset_[a] + 6);
  }
  if (reference_offset_ >= 0)
    state[reference_offset_] = mu_rest_;
}

void ReducedOrderLaw::evaluate(const PointStep& step, const double* state_n, Trial& t) const {
  for (std::size_t k = 0; k < unknown_.size(); ++k) {
    const int a = unknown_[k];
    if (laws_[uz(a)]->isLinear()) { // clustering only: sigma = L eps, no eigenstrain
      t.sigma[k] = L0_[uz(a)] * t.eps[k];
      t.T[k] = L0_[uz(a)];
      t.mu[k].setZero();
      continue;
    }
    const double* block_n = state_n + offset_[uz(a)];
    PointStep ps;
    ps.eps_n = Eigen::Map<const Vector6>(block_n);
    ps.eps = t.eps[k];
    ps.J_n = partitionJ(step.J_n, trace(ps.eps_n), trace(step.eps_n));
    ps.J = partitionJ(step.J, trace(ps.eps), trace(step.eps));
    ps.dt = step.dt;
    if (!(ps.J > 0 && ps.J_n > 0))
      fail(detail::concat("partition ", a, " would reach a volume ratio J = ", ps.J,
                          " (not positive)"));
    try {
      laws_[uz(a)]->update(ps, block_n + 6, t.state.data() + trial_offset_[k], t.sigma[k], &t.T[k]);
    } catch (const Error& e) {
      fail(detail::concat("partition ", a, ": ", e.message()));
    }
    t.mu[k] = t.eps[k] - L0inv_[uz(a)] * t.sigma[k];
  }
}

Eigen::MatrixXd ReducedOrderLaw::jacobian(const std::vector<Matrix6>& T,
                                          const Reference* ref) const {
  const std::size_t m = unknown_.size();
  const int n = model_.partitions();
  Eigen::MatrixXd K = Eigen::MatrixXd::Identity(6 * idx(m), 6 * idx(m));
  for (std::size_t l = 0; l < m; ++l) {
    const int a = unknown_[l];
    if (ref) { // delta I + G^(k l) (T_l - C0)
      const Matrix6 dT = T[l] - ref->C0;
      for (std::size_t k = 0; k < m; ++k)
        K.block<6, 6>(6 * idx(k), 6 * idx(l)) += ref->G[uz(unknown_[k] * n + a)] * dT;
      continue;
    }
    // I - L0^-1 T as L0^-1 (L0 - T): exactly zero where T = L0
    const Matrix6 dmu = L0inv_[uz(a)] * (L0_[uz(a)] - T[l]);
    for (std::size_t k = 0; k < m; ++k)
      K.block<6, 6>(6 * idx(k), 6 * idx(l)) -= model_.P[uz(unknown_[k] * n + a)] * dmu;
  }
  return K;
}

void ReducedOrderLaw::sensitivities(const std::vector<Matrix6>& T, const Reference* ref,
                                    Eigen::MatrixXd& deps, Eigen::MatrixXd& dmu) const {
  const std::size_t m = unknown_.size();
  Eigen::MatrixXd rhs(6 * idx(m), 6);
  for (std::size_t k = 0; k < m; ++k)
    rhs.block<6, 6>(6 * idx(k), 0) = ref ? Matrix6::Identity() : model_.A[uz(unknown_[k])];
  deps = jacobian(T, ref).partialPivLu().solve(rhs);
  dmu.resize(6 * idx(nonlinear_.size()), 6);
  for (std::size_t k = 0; k < nonlinear_.size(); ++k) {
    const int a = nonlinear_[k];
    const Index s = 6 * idx(uz(nl_slot_[k]));
    dmu.block<6, 6>(6 * idx(k), 0) =
        L0inv_[uz(a)] * (L0_[uz(a)] - T[uz(nl_slot_[k])]) * deps.block<6, 6>(s, 0);
  }
}

Matrix6 ReducedOrderLaw::coarseTangent(const std::vector<Matrix6>& T, const Eigen::MatrixXd& deps,
                                       const Eigen::MatrixXd& dmu) const {
  Matrix6 C = C_linear_;
  if (clustering_) {
    for (std::size_t k = 0; k < unknown_.size(); ++k)
      C += model_.fraction[uz(unknown_[k])] * T[k] * deps.block<6, 6>(6 * idx(k), 0);
    return C;
  }
  for (std::size_t k = 0; k < nonlinear_.size(); ++k)
    C += model_.fraction[uz(nonlinear_[k])] * T[k] * deps.block<6, 6>(6 * idx(k), 0) +
         B_[k] * dmu.block<6, 6>(6 * idx(k), 0);
  return C;
}

std::array<double, 2> ReducedOrderLaw::lameOf(double mu0) const {
  return {kappa0_ - 2 * mu0 / 3, mu0};
}

double ReducedOrderLaw::softestShear(const std::vector<Matrix6>& T) const {
  double mu = std::numeric_limits<double>::infinity();
  for (const Matrix6& Tk : T) // every phase has partitions
    mu = std::min(mu, isotropicShear(Tk));
  return mu;
}

Matrix6 ReducedOrderLaw::referenceTangent(const std::vector<Matrix6>& T, double mu0) const {
  const Reference ref(model_, lameOf(mu0));
  Eigen::MatrixXd deps, dmu;
  sensitivities(T, &ref, deps, dmu);
  return coarseTangent(T, deps, dmu);
}

double ReducedOrderLaw::stepReference(const Trial& t, const Vector6& eps_c, double last) const {
  const std::size_t phases = model_.phases.size();
  std::vector<Vector6> s(phases, Vector6::Zero()), e(phases, Vector6::Zero());
  std::vector<double> c(phases, 0.0);
  for (std::size_t k = 0; k < unknown_.size(); ++k) {
    const int a = unknown_[k];
    const std::size_t p = uz(model_.partition_phase[uz(a)]);
    const double f = model_.fraction[uz(a)];
    s[p] += f * t.sigma[k];
    e[p] += f * t.eps[k];
    c[p] += f;
  }
  const double small = 1e-10 * eps_c.cwiseAbs().maxCoeff();
  double mu = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < phases; ++p) {
    const double secant = secantShear(s[p] / c[p], e[p] / c[p], small);
    if (secant > 0 && std::isfinite(secant))
      mu = std::min(mu, secant);
  }
  if (!std::isfinite(mu))
    mu = last; // no phase strained in shear
  return std::max(mu, kShearFloor * mu_rest_);
}

Stiffness ReducedOrderLaw::elasticStiffness(double J) const {
  if (nonlinear_.empty())
    return Stiffness(C_linear_);
  std::vector<Matrix6> T;
  for (int a : unknown_)
    T.push_back(laws_[uz(a)]->elasticStiffness(J).matrix());
  if (clustering_)
    return Stiffness(referenceTangent(T, softestShear(T)));
  Eigen::MatrixXd deps, dmu;
  sensitivities(T, nullptr, deps, dmu);
  return Stiffness(coarseTangent(T, deps, dmu));
}

void ReducedOrderLaw::update(const PointStep& step, const double* state_n, double* state,
                             Vector6& sigma, Matrix6* tangent) const {
  updateWithInfo(step, state_n, state, sigma, tangent, nullptr);
}

void ReducedOrderLaw::updateWithInfo(const PointStep& step, const double* state_n, double* state,
                                     Vector6& sigma, Matrix6* tangent,
                                     ReducedOrderStepInfo* info) const {
  const std::size_t m = unknown_.size();
  if (nonlinear_.empty()) { // a linear cell: sigma = C eps, no state
    sigma = C_linear_ * step.eps;
    if (tangent)
      *tangent = C_linear_;
    if (info)
      *info = {0, 0.0, Eigen::MatrixXd(0, 6)};
    return;
  }
  Trial t(m, trial_state_size_);
  const Vector6 deps_c = step.eps - step.eps_n;
  for (std::size_t k = 0; k < m; ++k) {
    const int b = unknown_[k];
    t.eps[k] = Eigen::Map<const Vector6>(state_n + offset_[uz(b)]) +
               (clustering_ ? deps_c : Vector6(model_.A[uz(b)] * deps_c));
  }
  int iterations = 0;
  double norm = 0;
  Eigen::MatrixXd deps, dmu;
  double next = 0; // clustering: the next step's reference shear modulus
  Matrix6 C_T;
  if (clustering_) {
    // the step in the reference medium fitted at the end of the last one;
    // the fit to this step's answer is the next step's
    const double mu0 = state_n[reference_offset_];
    if (!(std::isfinite(mu0) && mu0 > 0))
      fail(detail::concat("the state's reference shear modulus is ", mu0,
                          " (not positive): a state not set by initState()?"));
    const Reference ref(model_, lameOf(mu0));
    solveStrains(step, state_n, &ref, t, iterations, norm);
    next = stepReference(t, step.eps, mu0);
    if (tangent || info) {
      sensitivities(t.T, &ref, deps, dmu);
      C_T = coarseTangent(t.T, deps, dmu);
    }
    sigma.setZero();
    for (std::size_t k = 0; k < m; ++k)
      sigma += model_.fraction[uz(unknown_[k])] * t.sigma[k];
  } else {
    solveStrains(step, state_n, nullptr, t, iterations, norm);
    // the average (eq. 33): linear partitions through C_linear_ and B_
    sigma = C_linear_ * step.eps;
    for (std::size_t k = 0; k < m; ++k)
      sigma += model_.fraction[uz(nonlinear_[k])] * t.sigma[k] + B_[k] * t.mu[k];
    if (tangent || info) {
      sensitivities(t.T, nullptr, deps, dmu);
      C_T = coarseTangent(t.T, deps, dmu);
    }
  }
  if (tangent)
    *tangent = C_T;
  if (info)
    *info = {iterations, norm, std::move(dmu)};
  accept(step, t, state); // every read of state_n is done (state may alias it)
  if (clustering_)
    state[reference_offset_] = next;
}

double ReducedOrderLaw::residual(const Vector6& eps_c, const Reference* ref, const Trial& t,
                                 Eigen::VectorXd& r) const {
  const std::size_t m = unknown_.size();
  const int n = model_.partitions();
  double scale = eps_c.cwiseAbs().maxCoeff();
  std::vector<Vector6> tau;
  if (ref)
    for (std::size_t l = 0; l < m; ++l)
      tau.push_back(t.sigma[l] - ref->C0 * t.eps[l]);
  for (std::size_t k = 0; k < m; ++k) {
    const int b = unknown_[k];
    Vector6 term = Vector6::Zero();
    if (ref) { // r = eps - eps^c + sum G (sigma - C0 eps)
      for (std::size_t l = 0; l < m; ++l)
        term += ref->G[uz(b * n + unknown_[l])] * tau[l];
      r.segment<6>(6 * idx(k)) = t.eps[k] - eps_c + term;
    } else { // r = eps - A eps^c - sum P mu
      for (std::size_t l = 0; l < m; ++l)
        term += model_.P[uz(b * n + unknown_[l])] * t.mu[l];
      r.segment<6>(6 * idx(k)) = t.eps[k] - model_.A[uz(b)] * eps_c - term;
    }
    // the size of the terms r sums: its round-off is relative to them (in
    // clustering the polarization term, whose parts cancel, is one of them)
    scale = std::max({scale, t.eps[k].cwiseAbs().maxCoeff(), t.mu[k].cwiseAbs().maxCoeff()});
    if (ref)
      scale = std::max(scale, term.cwiseAbs().maxCoeff());
  }
  // clustering: every partition is an unknown, and a nonlinear law's stress
  // carries its own tolerances, absolute at some level (GVBO: its overstress
  // iteration), which stop being small against stresses of strains near
  // zero (a membrane's first steps: 1e-23); a strain of 1e-14 is 1e-5 Pa in
  // a GPa material, below any load, so the test is relative to no less
  return ref ? std::max(scale, kStrainFloor) : scale;
}

void ReducedOrderLaw::solveStrains(const PointStep& step, const double* state_n,
                                   const Reference* ref, Trial& t, int& iterations,
                                   double& norm) const {
  const std::size_t m = unknown_.size();
  Eigen::VectorXd r(6 * idx(m));
  double last_norm = 0;
  // Newton with the Jacobian kept while it works: the partition tangents
  // leave out the moduli's change with J, so the iteration converges
  // linearly anyway where that matters; a Jacobian is formed and factored
  // again only when the residual fell by less than 4x in the last step.
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  for (;;) {
    evaluate(step, state_n, t);
    const double scale = residual(step.eps, ref, t, r);
    norm = r.lpNorm<Eigen::Infinity>();
    if (norm <= options_.tolerance * scale)
      return;
    if (iterations == options_.max_iterations || !std::isfinite(norm))
      fail(detail::concat("the Newton iteration of the partition strains did not converge: "
                          "residual ",
                          norm, " after ", iterations, " iterations (tolerance ",
                          options_.tolerance, " x ", scale, ")"));
    if (iterations == 0 || norm > 0.25 * last_norm)
      lu.compute(jacobian(t.T, ref));
    last_norm = norm;
    const Eigen::VectorXd dx = lu.solve(r);
    for (std::size_t k = 0; k < m; ++k)
      t.eps[k] -= dx.segment<6>(6 * idx(k));
    ++iterations;
  }
}

void ReducedOrderLaw::accept(const PointStep& step, const Trial& t, double* state) const {
  const std::size_t m = unknown_.size();
  const int n = model_.partitions();
  if (!clustering_)
    for (int e : linear_) { // their strains follow from the eigenstrains
      Vector6 eps_e = model_.A[uz(e)] * step.eps;
      for (std::size_t l = 0; l < m; ++l)
        eps_e += model_.P[uz(e * n + unknown_[l])] * t.mu[l];
      Eigen::Map<Vector6>(state + offset_[uz(e)]) = eps_e;
    }
  for (std::size_t k = 0; k < m; ++k) {
    const int a = unknown_[k];
    Eigen::Map<Vector6>(state + offset_[uz(a)]) = t.eps[k];
    if (laws_[uz(a)]->isLinear())
      continue;
    const auto begin = t.state.begin() + trial_offset_[k];
    std::copy(begin, begin + laws_[uz(a)]->stateSize(), state + offset_[uz(a)] + 6);
  }
}

Vector6 ReducedOrderLaw::partitionStress(int alpha, const double* block, double J) const {
  const ConstitutiveLaw& law = *laws_[uz(alpha)];
  if (law.kind() == LawKind::Gvbo)
    return Eigen::Map<const Vector6>(block + 6 + GvboState::kSigma);
  // any other law: the stress of a step that changes nothing
  PointStep ps;
  ps.eps_n = ps.eps = Eigen::Map<const Vector6>(block);
  ps.J_n = ps.J = J;
  std::vector<double> scratch(uz(law.stateSize()));
  Vector6 sigma;
  law.update(ps, block + 6, scratch.data(), sigma, nullptr);
  return sigma;
}

double ReducedOrderLaw::storedEnergy(const Vector6& sigma, const double* state, double J) const {
  if (nonlinear_.empty())
    return ConstitutiveLaw::storedEnergy(sigma, state, J); // C_linear_: sum c L A
  const int n = model_.partitions();
  double tr_c = 0;
  for (int a = 0; a < n; ++a)
    tr_c += model_.fraction[uz(a)] * trace(Eigen::Map<const Vector6>(state + offset_[uz(a)]));
  double W = 0;
  for (int a = 0; a < n; ++a) {
    const double* block = state + offset_[uz(a)];
    const Vector6 eps_a = Eigen::Map<const Vector6>(block);
    const double c = model_.fraction[uz(a)];
    if (laws_[uz(a)]->isLinear()) {
      W += c * 0.5 * eps_a.dot(L0_[uz(a)] * eps_a);
      continue;
    }
    const double J_a = partitionJ(J, trace(eps_a), tr_c);
    W += c * laws_[uz(a)]->storedEnergy(partitionStress(a, block, J_a), block + 6, J_a);
  }
  return W;
}

Matrix6 ReducedOrderLaw::nonlinearDispersion(const ReducedOrderStepInfo& info) const {
  const Index rows = 6 * idx(nonlinear_.size());
  LAMINA_CHECK(info.dmu_deps.rows() == rows && info.dmu_deps.cols() == 6,
               "nonlinear dispersion of '", entry_, "': d mu / d eps^c is ", info.dmu_deps.rows(),
               " x ", info.dmu_deps.cols(), ", expected ", rows, " x 6");
  if (rows == 0)
    return Matrix6::Zero(); // every d mu is zero
  const Eigen::MatrixXd& M = info.dmu_deps;
  const Matrix6 X = M.transpose() * (R_nl_ * M);
  const Matrix6 QM = Q_nl_ * M;
  // written symmetric term by term, so the result is symmetric to the bit
  return 0.5 * (X + X.transpose()) + (QM + QM.transpose());
}

} // namespace lamina::materials
