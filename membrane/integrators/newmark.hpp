#pragma once
/// @file newmark.hpp
/// @brief The Newmark scheme of the membrane paper (eq. 30) with HHT-alpha,
/// constraints, implicit drag, springs to the ground and rigid sets, stepping
/// the SecondOrderSystem of a linear structure (constant K).
///
/// Equation: M a + K u = F(t) + F_drag(v) + F_s(u) + R, with R the reactions
/// at the constrained DOFs (zero elsewhere) and F_s = -K_s u the springs to
/// the ground ([[spring]]; K_s diagonal, k per spring DOF). The springs are
/// linear: K below stands for K + K_s (in A, in K u~ and in R), and
/// forces().spring holds F_s for the energy balance (spring_work). One step (tau = dt, c = tau^2
/// beta2 / 2):
///   u~ = u_n + tau v_n + tau^2/2 (1 - beta2) a_n,  v~ = v_n + tau (1 - beta1) a_n
///   A a_{n+1} = F_{n+1} + F_drag,n+1 - K u~          (A = M + c K, set up once)
///   u_{n+1} = u~ + c a_{n+1},  v_{n+1} = v~ + beta1 tau a_{n+1}.
/// Constrained DOFs: rows and columns of A replaced by the identity, the
/// right-hand side there holds the prescribed acceleration (zero for a
/// constant velocity), K u~ keeps all columns so a moving node pulls its
/// neighbours. HHT-alpha (alpha < 0) weights the elastic and external forces
/// (1 + alpha) at n+1 and -alpha at n. Drag is implicit: fixed-point
/// iteration of a_{n+1} with F_drag evaluated at v_{n+1} (trapezoidal in
/// time, second order; it converges when beta1 tau |dF/dv| / m < 1, which
/// holds by orders of magnitude for air).
///
/// Rigid sets ([[rigid]]): the accelerations are condensed, a = T a_r
/// (rigid_condensation.hpp): A and the right-hand side become T^T A T and
/// T^T b, so each set takes one acceleration, its total force over its
/// total "mass" (the sum of its rows of A).
///
/// Reactions: R = M a + K u - F - F_drag - F_s at the constrained DOFs
/// (SecondOrderSystem::reactions, from M a + K u there). With the
/// works of energy.hpp, E_n - E_0 - W_n = 0 exactly in exact arithmetic for
/// beta1 = beta2 = 1/2 and alpha = 0 (the identity of the
/// average-acceleration rule).

#include "core/error.hpp"
#include "membrane/integrators/rigid_condensation.hpp"
#include "membrane/integrators/step_solver.hpp"
#include "membrane/integrators/time_integrator.hpp"
#include "membrane/model/block_matrix.hpp"
#include "membrane/system/second_order_system.hpp"

#include <memory>
#include <vector>

namespace lamina::membrane {

/// Newmark / HHT-alpha on a linear structure.
class Newmark final : public TimeIntegrator {
public:
  /// Builds A = M + c (K + K_s) with the constraints and the rigid sets' condensation and sets up
  /// its solver (settings from the model's time). Throws lamina::Error when @p system's structure
  /// has no constant stiffness, or the system has rigid surfaces in contact. @p system must
  /// outlive the scheme.
  explicit Newmark(const SecondOrderSystem& system);
  ~Newmark() override;
  void init(State& s) override;
  void step(State& s) override;
  double timeStep() const override { return system_.model().time.dt; }
  const StateForces& forces() const override { return cur_; }
  const StateForces& previousForces() const override { return prev_; }
  const Eigen::VectorXd& increment() const override { return du_; }
  std::string name() const override {
    return std::string(kIntegratorKindNames.name(IntegratorKind::Newmark));
  }
  SolverStats stats() const override;
  double setupSeconds() const override { return setup_s_; }
  /// Saves a_{n-1} (the CG start), the forces at t_n, the solver's history.
  void saveHistory(History& h) const override;
  void restoreHistory(const History& h) override;

private:
  /// The step's stages, in order (step() reads as the method of the file comment).
  /// u~, v~ of eq. (30) into ut_, vt_, and the solver's start a1_ = 2 a_n - a_{n-1}.
  void predict(const State& s);
  /// b_ = (1 + alpha) (F_{n+1} - K u~) - alpha (F_n + Fd_n - K u_n) (HHT-alpha; alpha = 0: the
  /// paper's).
  void assembleRightHandSide(const State& s, double t1);
  /// The constrained DOFs' accelerations ac_ that bring v_{n+1} to the
  /// prescribed velocity at @p t1; their columns of A move to b_.
  void prescribeAccelerations(double t1);
  /// Solves A a_{n+1} = b_ + (1 + alpha) F_drag (a1_), iterating on the drag
  /// at v_{n+1} (at most time.drag_iterations passes, to time.drag_tolerance).
  void solveAcceleration(const State& s, double t1);
  /// u_{n+1}, v_{n+1} and the increment (u1_, v1_, du_); throws
  /// DivergenceError (throwNonFinite) before a non-finite state is committed.
  void correct(const State& s, double t1);
  /// f.reaction at the state @p s (SecondOrderSystem::reactions).
  void reactions(const State& s, StateForces& f);
  [[noreturn]] void divergedInSolve(const State& s, const DivergenceError& e, double t1) const;

  const SecondOrderSystem& system_;
  const Model& model_;
  const ConstrainedDofs& cons_;
  const SparseMatrix& K_;      // the stiffness of the step: K + K_s (the system's)
  RigidCondensation rigid_;    // a = T a_r of the rigid sets
  SparseMatrix Afc_, Kc_, Mc_; // Kc_, Mc_: the constrained rows of K (no springs) and M
  BlockMatrix Kb_;             // K in 3x3 blocks for the per-step K u~
  std::unique_ptr<StepSolver> solver_;
  StateForces cur_, prev_, next_;
  Eigen::VectorXd a_prev_; // a_{n-1}: the CG start extrapolates a linearly
  Eigen::VectorXd ut_, vt_, ku_, b_, a1_, u1_, v1_, ac_, tmp_, du_, inertia_;
  double c_ = 0, setup_s_ = 0;
  int last_iterations_ = 0;
};

} // namespace lamina::membrane
