#include "membrane/simulation.hpp"

#include "core/error.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

namespace lamina::membrane {

namespace {
double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

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
} // namespace

Simulation::Simulation(const Model& model) : model_(model) {
  const auto& ts = model.time;
  LAMINA_CHECK(ts.dt > 0, "time step must be > 0");
  LAMINA_CHECK(ts.beta1 > 0, "beta1 must be > 0");
  const int ndof = model.numDofs();

  auto t0 = std::chrono::steady_clock::now();
  GlobalMatrices g = assemble(model.mesh, model.sections, ts.lumped);
  K_ = std::move(g.K);
  M_ = std::move(g.M);
  for (const auto& [node, m] : model.point_masses)
    for (int c = 0; c < 3; ++c)
      M_.coeffRef(3 * node + c, 3 * node + c) += m;
  assembly_s_ = seconds(t0);

  t0 = std::chrono::steady_clock::now();
  // eq. (30): A = M + tau^2/2 beta2 K (HHT: times 1 + alpha on K).
  c_ = 0.5 * ts.dt * ts.dt * ts.beta2;
  SparseMatrix A = M_; // local: the solver keeps its own copy or factor
  {
    const double ck = c_ * (1 + ts.hht_alpha);
    const Eigen::Index nnz = A.nonZeros();
    double* av = A.valuePtr();
    const double* kv = K_.valuePtr();
    for (Eigen::Index k = 0; k < nnz; ++k)
      av[k] += ck * kv[k];
  }
  std::vector<char> constrained(ndof, 0);
  for (size_t s = 0; s < model.constraints.size(); ++s) {
    const auto& con = model.constraints[s];
    for (size_t k = 0; k < con.dofs.size(); ++k) {
      cdofs_.push_back(con.dofs[k]);
      cset_.push_back(static_cast<int>(s));
      camp_.push_back(con.amplitude[k]);
      constrained[con.dofs[k]] = 1;
    }
  }
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
  Kb_ = BlockMatrix(K_);
  Kc_ = extractRows(K_, cdofs_);
  Mc_ = extractRows(M_, cdofs_);
  solver_ =
      std::make_unique<StepSolver>(A, ts.solver, ts.tolerance, ts.max_iterations, ts.projection);
  setup_s_ = seconds(t0);

  has_loads_ = !model.loads.empty();
  has_drag_ = !model.drags.empty();

  // Initial state.
  u_ = model.u0.size() == ndof ? model.u0 : Eigen::VectorXd::Zero(ndof);
  v_ = model.v0.size() == ndof ? model.v0 : Eigen::VectorXd::Zero(ndof);
  for (size_t k = 0; k < cdofs_.size(); ++k)
    v_[cdofs_[k]] = camp_[k] * model.constraints[cset_[k]].profile(0.0);
  f_ = Eigen::VectorXd::Zero(ndof);
  fd_ = Eigen::VectorXd::Zero(ndof);
  externalForce(0.0, f_);
  if (has_drag_)
    dragForce(v_, fd_);
  // Consistent initial acceleration: M a_0 = F_0 + Fd_0 - K u_0 on the free
  // DOFs, a_0 = 0 on the constrained ones.
  a_ = Eigen::VectorXd::Zero(ndof);
  multiply(K_, u_, ku_);
  b_ = f_ + fd_ - ku_;
  for (int d : cdofs_)
    b_[d] = 0;
  if (b_.norm() > 0) {
    SparseMatrix Mf = M_;
    for (int i = 0; i < ndof; ++i)
      for (SparseMatrix::InnerIterator it(Mf, i); it; ++it)
        if (constrained[i] || constrained[it.col()])
          it.valueRef() = (i == it.col()) ? 1.0 : 0.0;
    StepSolver ms(Mf, ts.solver, std::min(ts.tolerance, 1e-13), ts.max_iterations);
    ms.solve(b_, a_);
  }
  a_prev_ = a_;
  rc_.resize(static_cast<Eigen::Index>(cdofs_.size()));
  reactions(0.0, rc_);
  const Energy e = energy();
  e0_ = e.kinetic + e.strain;
  f1_ = f_;
  fd1_ = fd_;
  ac_ = Eigen::VectorXd::Zero(ndof);
}

Simulation::~Simulation() = default;

void Simulation::externalForce(double t, Eigen::VectorXd& f) const {
  f.setZero(model_.numDofs());
  for (const auto& l : model_.loads) {
    const double s = l.profile(t);
    if (s != 0)
      f += s * l.pattern;
  }
}

void Simulation::dragForce(const Eigen::VectorXd& v, Eigen::VectorXd& f) const {
  // Drag paper eqs. (1)-(3): F_i = 1/2 rho_f V_i^2 A_i C_d along the normal
  // (e_z of the flat membrane), opposite to the normal motion.
  f.setZero(model_.numDofs());
  for (const auto& d : model_.drags)
    for (size_t k = 0; k < d.nodes.size(); ++k) {
      const int i = d.nodes[k];
      const double vn = v[3 * i + 2];
      const double speed = d.resultant ? v.segment<3>(3 * i).norm() : std::abs(vn);
      // 'normal': V = |v_n|, F = -q V v_n; 'resultant': V = |v|, direction by sign(v_n).
      const double q = 0.5 * d.fluid_density * d.cd * d.area[k];
      f[3 * i + 2] -= d.resultant ? q * speed * speed *
                                        (vn > 0   ? 1.0
                                         : vn < 0 ? -1.0
                                                  : 0.0)
                                  : q * speed * vn;
    }
}

void Simulation::reactions(double t, Eigen::VectorXd& r) const {
  // R = M a + K u - F - F_drag at the constrained DOFs.
  (void)t;
  if (cdofs_.empty())
    return;
  r = Mc_ * a_ + Kc_ * u_;
  for (size_t k = 0; k < cdofs_.size(); ++k)
    r[k] -= f_[cdofs_[k]] + fd_[cdofs_[k]];
}

void Simulation::step() {
  const auto& ts = model_.time;
  const double tau = ts.dt, alpha = ts.hht_alpha;
  const double t1 = (n_ + 1) * tau;
  const int ndof = model_.numDofs();

  // Predictors of eq. (30).
  ut_ = u_ + tau * v_ + (0.5 * tau * tau * (1 - ts.beta2)) * a_;
  vt_ = v_ + (tau * (1 - ts.beta1)) * a_;
  if (has_loads_)
    externalForce(t1, f1_);
  Kb_.multiply(ut_, ku_);
  // Right-hand side without drag: (1+alpha)(F1 - K u~) - alpha (F_n + Fd_n - K u_n).
  b_ = (1 + alpha) * (f1_ - ku_);
  if (alpha != 0) {
    multiply(K_, u_, tmp_);
    b_ -= alpha * (f_ + fd_ - tmp_);
  }
  // Prescribed accelerations so that v_{n+1} hits the prescribed velocity.
  bool moving_acc = false;
  for (size_t k = 0; k < cdofs_.size(); ++k) {
    const int d = cdofs_[k];
    const double vp = camp_[k] * model_.constraints[cset_[k]].profile(t1);
    ac_[d] = (vp - vt_[d]) / (ts.beta1 * tau);
    if (ac_[d] != 0)
      moving_acc = true;
  }
  if (moving_acc)
    b_ -= Afc_ * ac_;

  // Warm start: linear extrapolation of the acceleration history.
  a1_ = 2 * a_ - a_prev_;
  last_iterations_ = 0;
  const int passes = has_drag_ ? ts.drag_iterations : 1;
  for (int pass = 0; pass < passes; ++pass) {
    tmp_ = b_;
    if (has_drag_) {
      v1_ = vt_ + (ts.beta1 * tau) * a1_;
      dragForce(v1_, fd1_);
      tmp_ += (1 + alpha) * fd1_;
    }
    for (int d : cdofs_)
      tmp_[d] = ac_[d];
    Eigen::VectorXd previous;
    if (has_drag_)
      previous = a1_;
    try {
      last_iterations_ += solver_->solve(tmp_, a1_);
    } catch (const DivergenceError& e) {
      // Name the time and the node moving most in the last finite state.
      int worst = 0;
      double big = -1;
      for (int i = 0; i < ndof / 3; ++i) {
        const double s = u_.segment<3>(3 * i).norm() + v_.segment<3>(3 * i).norm();
        if (!(s <= big)) {
          big = s;
          worst = i;
        }
      }
      const auto& p = model_.mesh.nodes[worst];
      std::ostringstream os;
      os << e.message() << " at t = " << t1 << " s (step " << n_ + 1 << "), largest motion at node "
         << worst << " (" << p.x() << ", " << p.y() << ")";
      throw DivergenceError(os.str());
    }
    if (!has_drag_)
      break;
    if ((a1_ - previous).norm() <= ts.drag_tolerance * (a1_.norm() + 1e-300))
      break;
  }
  if (has_drag_) {
    // Drag consistent with the final a_{n+1}, as used in the balance below.
    v1_ = vt_ + (ts.beta1 * tau) * a1_;
    dragForce(v1_, fd1_);
  }
  u1_ = ut_ + c_ * a1_;
  v1_ = vt_ + (ts.beta1 * tau) * a1_;

  // Non-finite state: stop before committing it.
  if (!u1_.allFinite() || !v1_.allFinite() || !a1_.allFinite()) {
    int bad = 0;
    for (int i = 0; i < ndof; ++i)
      if (!std::isfinite(u1_[i]) || !std::isfinite(v1_[i]) || !std::isfinite(a1_[i])) {
        bad = i / 3;
        break;
      }
    const auto& p = model_.mesh.nodes[bad];
    std::ostringstream os;
    os << "non-finite state at t = " << t1 << " s (step " << n_ + 1 << "), node " << bad << " at ("
       << p.x() << ", " << p.y() << ")";
    throw DivergenceError(os.str());
  }

  // Works by the trapezoidal rule over the step.
  const Eigen::VectorXd du = u1_ - u_;
  if (has_loads_)
    w_ext_ += 0.5 * du.dot(f_ + f1_);
  if (has_drag_)
    w_drag_ += 0.5 * du.dot(fd_ + fd1_);

  // Commit.
  a_prev_ = a_;
  std::swap(u_, u1_);
  std::swap(v_, v1_);
  std::swap(a_, a1_);
  std::swap(f_, f1_);
  if (!has_loads_)
    f1_ = f_;
  std::swap(fd_, fd1_);
  t_ = t1;
  ++n_;
  if (!cdofs_.empty()) {
    rc1_.resize(rc_.size());
    reactions(t_, rc1_);
    for (size_t k = 0; k < cdofs_.size(); ++k)
      w_reac_ += 0.5 * du[cdofs_[k]] * (rc_[k] + rc1_[k]);
    std::swap(rc_, rc1_);
  }
}

Energy Simulation::energy() const {
  Energy e;
  Eigen::VectorXd y;
  multiply(M_, v_, y);
  e.kinetic = 0.5 * v_.dot(y);
  multiply(K_, u_, y);
  e.strain = 0.5 * u_.dot(y);
  e.external_work = w_ext_;
  e.reaction_work = w_reac_;
  e.drag_work = w_drag_;
  e.balance = e.kinetic + e.strain - e0_ - w_ext_ - w_reac_ - w_drag_;
  return e;
}

std::vector<Eigen::Vector3d> Simulation::reactionSums() const {
  std::vector<Eigen::Vector3d> s(model_.constraints.size(), Eigen::Vector3d::Zero());
  for (size_t k = 0; k < cdofs_.size(); ++k)
    s[cset_[k]][cdofs_[k] % 3] += rc_[k];
  return s;
}

Eigen::Vector3d Simulation::dragSum() const {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  if (fd_.size() == 0)
    return s;
  for (int i = 0; i < model_.mesh.numNodes(); ++i)
    s += fd_.segment<3>(3 * i);
  return s;
}

} // namespace lamina::membrane
