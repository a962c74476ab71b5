#include "materials/reduced_order_law.hpp"

#include "core/error.hpp"
#include "materials/gvbo_law.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
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
  offset_.assign(uz(n), -1);
  if (!nonlinear_.empty())
    for (int a = 0; a < n; ++a) {
      offset_[uz(a)] = state_size_;
      state_size_ += 6 + laws_[uz(a)]->stateSize();
    }
  for (int a : nonlinear_) {
    trial_offset_.push_back(trial_state_size_);
    trial_state_size_ += laws_[uz(a)]->stateSize();
  }
  C_linear_.setZero();
  for (int e : linear_)
    C_linear_ += model_.fraction[uz(e)] * L0_[uz(e)] * model_.A[uz(e)];
  const std::size_t m = nonlinear_.size();
  B_.assign(m, Matrix6::Zero());
  R_nl_.resize(6 * idx(m), 6 * idx(m));
  Q_nl_.resize(6, 6 * idx(m));
  for (std::size_t k = 0; k < m; ++k) {
    const int a = nonlinear_[k];
    for (int e : linear_)
      B_[k] += model_.fraction[uz(e)] * L0_[uz(e)] * model_.P[uz(e * n + a)];
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
}

void ReducedOrderLaw::evaluate(const PointStep& step, const double* state_n, Trial& t) const {
  for (std::size_t k = 0; k < nonlinear_.size(); ++k) {
    const int a = nonlinear_[k];
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

Eigen::MatrixXd ReducedOrderLaw::jacobian(const std::vector<Matrix6>& T) const {
  const std::size_t m = nonlinear_.size();
  const int n = model_.partitions();
  Eigen::MatrixXd K = Eigen::MatrixXd::Identity(6 * idx(m), 6 * idx(m));
  for (std::size_t l = 0; l < m; ++l) {
    const int a = nonlinear_[l];
    // I - L0^-1 T as L0^-1 (L0 - T): exactly zero where T = L0
    const Matrix6 dmu = L0inv_[uz(a)] * (L0_[uz(a)] - T[l]);
    for (std::size_t k = 0; k < m; ++k)
      K.block<6, 6>(6 * idx(k), 6 * idx(l)) -= model_.P[uz(nonlinear_[k] * n + a)] * dmu;
  }
  return K;
}

void ReducedOrderLaw::sensitivities(const std::vector<Matrix6>& T, Eigen::MatrixXd& deps,
                                    Eigen::MatrixXd& dmu) const {
  const std::size_t m = nonlinear_.size();
  Eigen::MatrixXd A_nl(6 * idx(m), 6);
  for (std::size_t k = 0; k < m; ++k)
    A_nl.block<6, 6>(6 * idx(k), 0) = model_.A[uz(nonlinear_[k])];
  deps = jacobian(T).partialPivLu().solve(A_nl);
  dmu.resize(6 * idx(m), 6);
  for (std::size_t k = 0; k < m; ++k) {
    const int a = nonlinear_[k];
    dmu.block<6, 6>(6 * idx(k), 0) =
        L0inv_[uz(a)] * (L0_[uz(a)] - T[k]) * deps.block<6, 6>(6 * idx(k), 0);
  }
}

Matrix6 ReducedOrderLaw::coarseTangent(const std::vector<Matrix6>& T, const Eigen::MatrixXd& deps,
                                       const Eigen::MatrixXd& dmu) const {
  Matrix6 C = C_linear_;
  for (std::size_t k = 0; k < nonlinear_.size(); ++k)
    C += model_.fraction[uz(nonlinear_[k])] * T[k] * deps.block<6, 6>(6 * idx(k), 0) +
         B_[k] * dmu.block<6, 6>(6 * idx(k), 0);
  return C;
}

Stiffness ReducedOrderLaw::elasticStiffness(double J) const {
  if (nonlinear_.empty())
    return Stiffness(C_linear_);
  std::vector<Matrix6> T;
  for (int a : nonlinear_)
    T.push_back(laws_[uz(a)]->elasticStiffness(J).matrix());
  Eigen::MatrixXd deps, dmu;
  sensitivities(T, deps, dmu);
  return Stiffness(coarseTangent(T, deps, dmu));
}

void ReducedOrderLaw::update(const PointStep& step, const double* state_n, double* state,
                             Vector6& sigma, Matrix6* tangent) const {
  updateWithInfo(step, state_n, state, sigma, tangent, nullptr);
}

void ReducedOrderLaw::updateWithInfo(const PointStep& step, const double* state_n, double* state,
                                     Vector6& sigma, Matrix6* tangent,
                                     ReducedOrderStepInfo* info) const {
  const std::size_t m = nonlinear_.size();
  if (m == 0) { // a linear cell: sigma = (sum c L A) eps, no state
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
    const int b = nonlinear_[k];
    t.eps[k] = Eigen::Map<const Vector6>(state_n + offset_[uz(b)]) + model_.A[uz(b)] * deps_c;
  }
  int iterations = 0;
  double norm = 0;
  solveStrains(step, state_n, t, iterations, norm);
  // the average (eq. 33): linear partitions through C_linear_ and B_
  sigma = C_linear_ * step.eps;
  for (std::size_t k = 0; k < m; ++k)
    sigma += model_.fraction[uz(nonlinear_[k])] * t.sigma[k] + B_[k] * t.mu[k];
  if (tangent || info) {
    Eigen::MatrixXd deps, dmu;
    sensitivities(t.T, deps, dmu);
    if (tangent)
      *tangent = coarseTangent(t.T, deps, dmu);
    if (info)
      *info = {iterations, norm, std::move(dmu)};
  }
  accept(step, t, state); // every read of state_n is done (state may alias it)
}

void ReducedOrderLaw::solveStrains(const PointStep& step, const double* state_n, Trial& t,
                                   int& iterations, double& norm) const {
  const std::size_t m = nonlinear_.size();
  const int n = model_.partitions();
  Eigen::VectorXd r(6 * idx(m));
  double last_norm = 0;
  // Newton with the Jacobian kept while it works: the partition tangents
  // leave out the moduli's change with J, so the iteration converges
  // linearly anyway where that matters; a Jacobian is formed and factored
  // again only when the residual fell by less than 4x in the last step.
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  for (;;) {
    evaluate(step, state_n, t);
    double scale = step.eps.cwiseAbs().maxCoeff();
    for (std::size_t k = 0; k < m; ++k) {
      const int b = nonlinear_[k];
      Vector6 rb = t.eps[k] - model_.A[uz(b)] * step.eps;
      for (std::size_t l = 0; l < m; ++l)
        rb -= model_.P[uz(b * n + nonlinear_[l])] * t.mu[l];
      r.segment<6>(6 * idx(k)) = rb;
      // the size of the terms r sums: its round-off is relative to them
      scale = std::max({scale, t.eps[k].cwiseAbs().maxCoeff(), t.mu[k].cwiseAbs().maxCoeff()});
    }
    norm = r.lpNorm<Eigen::Infinity>();
    if (norm <= options_.tolerance * scale)
      return;
    if (iterations == options_.max_iterations || !std::isfinite(norm))
      fail(detail::concat("the Newton iteration of the partition strains did not converge: "
                          "residual ",
                          norm, " after ", iterations, " iterations (tolerance ",
                          options_.tolerance, " x ", scale, ")"));
    if (iterations == 0 || norm > 0.25 * last_norm)
      lu.compute(jacobian(t.T));
    last_norm = norm;
    const Eigen::VectorXd dx = lu.solve(r);
    for (std::size_t k = 0; k < m; ++k)
      t.eps[k] -= dx.segment<6>(6 * idx(k));
    ++iterations;
  }
}

void ReducedOrderLaw::accept(const PointStep& step, const Trial& t, double* state) const {
  const std::size_t m = nonlinear_.size();
  const int n = model_.partitions();
  for (int e : linear_) {
    Vector6 eps_e = model_.A[uz(e)] * step.eps;
    for (std::size_t l = 0; l < m; ++l)
      eps_e += model_.P[uz(e * n + nonlinear_[l])] * t.mu[l];
    Eigen::Map<Vector6>(state + offset_[uz(e)]) = eps_e;
  }
  for (std::size_t k = 0; k < m; ++k) {
    const int a = nonlinear_[k];
    Eigen::Map<Vector6>(state + offset_[uz(a)]) = t.eps[k];
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
