#include "membrane/integrators/newmark.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace lamina::membrane {

namespace {

/// Rows @p rows of @p A as an |rows| x cols matrix.
SparseMatrix extractRows(const SparseMatrix& A, const std::vector<int>& rows) {
  SparseMatrix R(static_cast<Eigen::Index>(rows.size()), A.cols());
  std::vector<Eigen::Triplet<double>> t;
  for (size_t k = 0; k < rows.size(); ++k)
    for (SparseMatrix::InnerIterator it(A, rows[k]); it; ++it)
      t.emplace_back(static_cast<int>(k), static_cast<int>(it.col()), it.value());
  R.setFromTriplets(t.begin(), t.end());
  return R;
}

/// The correctors on the DOFs [@p i0, @p i1) in lanes: u1 = ut + c a1,
/// v1 = vt + cw a1, du = u1 - u. @return how many DOFs there have u1, v1
/// or a1 not finite.
LAMINA_VECTOR_CLONES int correctLanes(const double* __restrict ut, const double* __restrict vt,
                                      const double* __restrict a1, const double* __restrict u,
                                      double c, double cw, double* __restrict u1,
                                      double* __restrict v1, double* __restrict du, int i0,
                                      int i1) {
  core::LaneMask bad = 0;
#pragma omp simd reduction(+ : bad)
  for (int i = i0; i < i1; ++i) {
    const double x = ut[i] + c * a1[i];
    const double w = vt[i] + cw * a1[i];
    u1[i] = x;
    v1[i] = w;
    du[i] = x - u[i];
    bad += 1 - core::finiteLane(x) * core::finiteLane(w) * core::finiteLane(a1[i]);
  }
  return static_cast<int>(bad);
}

const SparseMatrix& requireStiffness(const SecondOrderSystem& system) {
  if (!system.stiffness())
    throw Error("the Newmark scheme needs the linear model (a constant stiffness K); "
                "use time.integrator = \"explicit\" for the large-deflection model");
  if (system.hasContact())
    throw Error("the Newmark scheme does not take rigid surfaces in contact (a one-sided, "
                "nonlinear force); use time.integrator = \"explicit\"");
  return *system.stiffness();
}
} // namespace

Newmark::Newmark(const SecondOrderSystem& system)
    : system_(system), model_(system.model()), cons_(system.constraints()),
      K_(requireStiffness(system)), rigid_(system.rigidSets(), system.numDofs()) {
  const auto& ts = model_.time;
  const ConstrainedDofs& cons = cons_;
  const Structure& structure = system.structure();
  LAMINA_CHECK(ts.dt > 0, "time step must be > 0");
  LAMINA_CHECK(ts.beta1 > 0, "beta1 must be > 0");
  const int ndof = structure.numDofs();
  const auto t0 = std::chrono::steady_clock::now();
  // eq. (30): A = M + tau^2/2 beta2 K (HHT: times 1 + alpha on K; K with the springs).
  c_ = 0.5 * ts.dt * ts.dt * ts.beta2;
  SparseMatrix A = structure.mass(); // local: the solver keeps its own copy or factor
  {
    const double ck = c_ * (1 + ts.hht_alpha);
    const Eigen::Index nnz = A.nonZeros();
    double* av = A.valuePtr();
    const double* kv = K_.valuePtr();
    for (Eigen::Index k = 0; k < nnz; ++k)
      av[k] += ck * kv[k];
  }
  const auto& constrained = cons.mask();
  // Constrained rows/columns of A -> identity; the columns move to Afc so a
  // non-zero prescribed acceleration still reaches the free rows.
  {
    std::vector<Eigen::Triplet<double>> fc;
    for (int i = 0; i < ndof; ++i)
      for (SparseMatrix::InnerIterator it(A, i); it; ++it) {
        const int j = static_cast<int>(it.col());
        if (constrained[i]) {
          it.valueRef() = (i == j) ? 1.0 : 0.0;
        } else if (constrained[j]) {
          fc.emplace_back(i, j, it.value());
          it.valueRef() = 0.0;
        }
      }
    Afc_.resize(ndof, ndof);
    Afc_.setFromTriplets(fc.begin(), fc.end());
  }
  A = rigid_.condense(A); // the free rows of Afc_ are condensed with b
  Kb_ = BlockMatrix(K_);
  Kc_ = extractRows(*structure.stiffness(), cons.dofs()); // the system subtracts F_s
  Mc_ = extractRows(structure.mass(), cons.dofs());
  solver_ =
      std::make_unique<StepSolver>(A, ts.solver, ts.tolerance, ts.max_iterations, ts.projection);
  setup_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Newmark::~Newmark() = default;

void Newmark::init(State& s) {
  const auto& ts = model_.time;
  const int ndof = system_.numDofs();
  cur_.external = Eigen::VectorXd::Zero(ndof);
  cur_.drag = Eigen::VectorXd::Zero(ndof);
  system_.external(s.t, s.u, cur_.external);
  if (system_.hasDrag())
    system_.drag(s.u, s.v, cur_.drag);
  if (system_.hasSprings())
    system_.springs(s.u, cur_.spring);
  // Consistent initial acceleration: M a_0 = F_0 + Fd_0 - (K + K_s) u_0 on the
  // free DOFs (condensed on the rigid sets), a_0 = 0 on the constrained ones.
  s.a = Eigen::VectorXd::Zero(ndof);
  multiply(K_, s.u, ku_);
  b_ = cur_.external + cur_.drag - ku_;
  for (int d : cons_.dofs())
    b_[d] = 0;
  if (b_.norm() > 0) {
    const auto& constrained = cons_.mask();
    SparseMatrix Mf = system_.mass();
    for (int i = 0; i < ndof; ++i)
      for (SparseMatrix::InnerIterator it(Mf, i); it; ++it)
        if (constrained[i] || constrained[it.col()])
          it.valueRef() = (i == it.col()) ? 1.0 : 0.0;
    Mf = rigid_.condense(Mf);
    rigid_.restrict(b_);
    StepSolver ms(Mf, ts.solver, std::min(ts.tolerance, 1e-13), ts.max_iterations);
    ms.solve(b_, s.a);
    rigid_.expand(s.a);
  }
  a_prev_ = s.a;
  reactions(s, cur_);
  prev_ = cur_;
  next_ = cur_;
  du_ = Eigen::VectorXd::Zero(ndof);
  ac_ = Eigen::VectorXd::Zero(ndof);
}

void Newmark::reactions(const State& s, StateForces& f) {
  // M a + K u at the constrained DOFs; the system subtracts the forces.
  if (cons_.empty())
    return;
  inertia_ = Mc_ * s.a + Kc_ * s.u;
  system_.reactions(inertia_, f);
}

void Newmark::divergedInSolve(const State& s, const DivergenceError& e, double t1) const {
  // Name the time and the node moving most in the last finite state.
  int worst = 0;
  double big = -1;
  for (int i = 0; i < system_.numDofs() / 3; ++i) {
    const double m = s.u.segment<3>(3 * i).norm() + s.v.segment<3>(3 * i).norm();
    if (!(m <= big)) {
      big = m;
      worst = i;
    }
  }
  const auto& p = model_.mesh.nodes[worst];
  std::ostringstream os;
  os << e.message() << " at t = " << t1 << " s (step " << s.step + 1 << "), largest motion at node "
     << model_.mesh.nodeLabel(worst) << " (" << p.x() << ", " << p.y() << ")";
  throw DivergenceError(os.str());
}

void Newmark::step(State& s) {
  const double t1 = static_cast<double>(s.step + 1) * model_.time.dt;
  predict(s);
  assembleRightHandSide(s, t1);
  prescribeAccelerations(t1);
  solveAcceleration(s, t1);
  correct(s, t1);
  if (system_.hasSprings())
    system_.springs(u1_, next_.spring); // F_s at t_{n+1}, for the spring work
  // Commit (a_n <- a_{n+1}, then a_{n-1} <- a_n by swaps).
  commitStep(s, t1, u1_, v1_, a1_);
  std::swap(a_prev_, a1_);
  std::swap(prev_, cur_);
  std::swap(cur_, next_);
  reactions(s, cur_);
}

void Newmark::predict(const State& s) {
  // Predictors of eq. (30), and the CG start: linear extrapolation of the
  // acceleration history (one threaded pass; these vector loops are a
  // fifth of a step at 300 x 300 when run one after the other on one thread).
  const auto& ts = model_.time;
  const double tau = ts.dt;
  const int n = system_.numDofs();
  const double cu = 0.5 * tau * tau * (1 - ts.beta2), cv = tau * (1 - ts.beta1);
  ut_.resize(n);
  vt_.resize(n);
  a1_.resize(n);
  const double *u = s.u.data(), *v = s.v.data(), *a = s.a.data(), *ap = a_prev_.data();
  double *ut = ut_.data(), *vt = vt_.data(), *a1 = a1_.data();
#pragma omp parallel for schedule(static) if (n > kParallelDofs)
  for (int i = 0; i < n; ++i) {
    ut[i] = u[i] + tau * v[i] + cu * a[i];
    vt[i] = v[i] + cv * a[i];
    a1[i] = 2 * a[i] - ap[i];
  }
}

void Newmark::assembleRightHandSide(const State& s, double t1) {
  const double alpha = model_.time.hht_alpha;
  const int n = system_.numDofs();
  if (system_.hasExternal())
    system_.external(t1, ut_, next_.external);
  Kb_.multiply(ut_, ku_);
  // Right-hand side without drag: (1+alpha)(F1 - K u~) - alpha (F_n + Fd_n - K u_n).
  b_.resize(n);
  {
    const double *f = next_.external.data(), *ku = ku_.data();
    double* b = b_.data();
#pragma omp parallel for schedule(static) if (n > kParallelDofs)
    for (int i = 0; i < n; ++i)
      b[i] = (1 + alpha) * (f[i] - ku[i]);
  }
  if (alpha != 0) {
    multiply(K_, s.u, tmp_);
    b_ -= alpha * (cur_.external + cur_.drag - tmp_);
  }
}

void Newmark::prescribeAccelerations(double t1) {
  // Prescribed accelerations so that v_{n+1} hits the prescribed velocity.
  const auto& ts = model_.time;
  bool moving_acc = false;
  for (size_t k = 0; k < cons_.size(); ++k) {
    const int d = cons_.dofs()[k];
    ac_[d] = (cons_.velocity(k, t1) - vt_[d]) / (ts.beta1 * ts.dt);
    if (ac_[d] != 0)
      moving_acc = true;
  }
  if (moving_acc)
    b_ -= Afc_ * ac_;
}

void Newmark::solveAcceleration(const State& s, double t1) {
  const auto& ts = model_.time;
  const double tau = ts.dt, alpha = ts.hht_alpha;
  const bool has_drag = system_.hasDrag();
  last_iterations_ = 0;
  const int passes = has_drag ? ts.drag_iterations : 1;
  for (int pass = 0; pass < passes; ++pass) {
    if (has_drag)
      tmp_ = b_;
    else
      std::swap(tmp_, b_); // b_ is not needed again
    if (has_drag) {
      v1_ = vt_ + (ts.beta1 * tau) * a1_;
      system_.drag(ut_, v1_, next_.drag);
      tmp_ += (1 + alpha) * next_.drag;
    }
    for (int d : cons_.dofs())
      tmp_[d] = ac_[d];
    Eigen::VectorXd previous;
    if (has_drag)
      previous = a1_;
    rigid_.restrict(tmp_);
    rigid_.zeroSlaves(a1_); // the condensed solution's value there
    try {
      last_iterations_ += solver_->solve(tmp_, a1_);
    } catch (const DivergenceError& e) {
      divergedInSolve(s, e, t1);
    }
    rigid_.expand(a1_);
    if (!has_drag)
      break;
    if ((a1_ - previous).norm() <= ts.drag_tolerance * (a1_.norm() + 1e-300))
      break;
  }
  if (has_drag) {
    // Drag consistent with the final a_{n+1}, as used in the balance.
    v1_ = vt_ + (ts.beta1 * tau) * a1_;
    system_.drag(ut_, v1_, next_.drag);
  }
}

void Newmark::correct(const State& s, double t1) {
  // u_{n+1}, v_{n+1} and the increment in one threaded pass of lanes,
  // counting non-finite values on the way.
  const int n = system_.numDofs();
  u1_.resize(n);
  v1_.resize(n);
  du_.resize(n);
  int non_finite = 0;
  {
    const double cw = model_.time.beta1 * model_.time.dt, c = c_;
    const double *ut = ut_.data(), *vt = vt_.data(), *a1 = a1_.data(), *u = s.u.data();
    double *u1 = u1_.data(), *v1 = v1_.data(), *du = du_.data();
#pragma omp parallel reduction(+ : non_finite) if (n > kParallelDofs)
    {
      const auto [i0, i1] = core::threadRange(n);
      non_finite += correctLanes(ut, vt, a1, u, c, cw, u1, v1, du, i0, i1);
    }
  }
  // Non-finite state: stop before committing it.
  if (non_finite > 0)
    throwNonFinite(model_.mesh, s, t1, u1_, v1_, a1_);
}

void Newmark::saveHistory(History& h) const {
  h["a_prev"] = a_prev_;
  h["last_iterations"] = Eigen::VectorXd::Constant(1, last_iterations_);
  saveForces("forces/", cur_, h);
  solver_->saveHistory("solver/", h);
}

void Newmark::restoreHistory(const History& h) {
  const Eigen::Index n = system_.numDofs();
  a_prev_ = historyEntry(h, "a_prev", n);
  last_iterations_ = static_cast<int>(
      historyInteger(h, "last_iterations", 1, 0, 0, std::numeric_limits<int>::max()));
  restoreForces("forces/", h, cur_); // every force of init(), with its size
  solver_->restoreHistory("solver/", h);
  prev_ = cur_; // as after init(): the next step overwrites what it reads of next_
  next_ = cur_;
}

SolverStats Newmark::stats() const {
  return {solver_->solves(), solver_->totalIterations(), last_iterations_};
}

} // namespace lamina::membrane
