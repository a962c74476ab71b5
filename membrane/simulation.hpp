#pragma once
/// @file simulation.hpp
/// @brief The Newmark time stepper of the membrane paper (eq. 30) with
/// constraints, reactions, drag and energy bookkeeping.
///
/// Equation: M a + K u = F(t) + F_drag(v) + R, with R the reactions at the
/// constrained DOFs (zero elsewhere). One step (tau = dt, c = tau^2 beta2 / 2):
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
/// Energy: T = v.Mv/2, U = u.Ku/2; works by the trapezoidal rule,
/// W += (u_{n+1} - u_n).(F_n + F_{n+1})/2 (same for reactions and drag). For
/// beta1 = beta2 = 1/2 and alpha = 0, E_n - E_0 - W_n = 0 exactly in exact
/// arithmetic (the identity of the average-acceleration rule).

#include "membrane/model.hpp"
#include "membrane/step_solver.hpp"

#include <Eigen/Dense>

#include <memory>
#include <vector>

namespace lamina::membrane {

/// Energies and works at one time (J).
struct Energy {
  double kinetic = 0;       ///< v.Mv / 2
  double strain = 0;        ///< u.Ku / 2
  double external_work = 0; ///< work of the loads since t = 0
  double reaction_work = 0; ///< work of the constraint reactions since t = 0
  double drag_work = 0;     ///< work of the drag since t = 0 (<= 0: dissipated)
  double balance = 0;       ///< E - E_0 - W (all works); round-off for the paper's scheme
};

/// A running simulation of one Model.
class Simulation {
public:
  /// Assembles K and M, builds A with the constraints, sets up its solver
  /// and the initial state (consistent initial acceleration).
  explicit Simulation(const Model& model);
  ~Simulation();

  /// Advances one step. On a non-finite state the step is not committed
  /// (the state stays the last finite one) and lamina::DivergenceError is
  /// thrown naming the time and the node.
  void step();

  /// @return current time (s)
  double time() const { return t_; }
  /// @return number of steps taken
  long steps() const { return n_; }
  /// @return displacements (3 per node)
  const Eigen::VectorXd& u() const { return u_; }
  /// @return velocities
  const Eigen::VectorXd& v() const { return v_; }
  /// @return accelerations
  const Eigen::VectorXd& a() const { return a_; }
  /// @return energies now (costs two SpMV)
  Energy energy() const;
  /// @return energy at t = 0 (T + U)
  double initialEnergy() const { return e0_; }
  /// @return reaction force summed per constraint set (N), current step
  std::vector<Eigen::Vector3d> reactionSums() const;
  /// @return drag force summed over all nodes (N), current step
  Eigen::Vector3d dragSum() const;
  /// @return global stiffness
  const SparseMatrix& K() const { return K_; }
  /// @return global mass (with point masses)
  const SparseMatrix& M() const { return M_; }
  /// @return seconds spent assembling K and M
  double assemblySeconds() const { return assembly_s_; }
  /// @return seconds spent building A and setting up its solver
  double setupSeconds() const { return setup_s_; }
  /// @return iterations of the last solve (sum over drag iterations)
  int lastIterations() const { return last_iterations_; }
  /// @return the solver (iteration statistics)
  const StepSolver& solver() const { return *solver_; }
  /// @return the model
  const Model& model() const { return model_; }

private:
  void externalForce(double t, Eigen::VectorXd& f) const;
  void dragForce(const Eigen::VectorXd& v, Eigen::VectorXd& f) const;
  void reactions(double t, Eigen::VectorXd& r) const;

  const Model& model_;
  SparseMatrix K_, M_, Afc_, Kc_, Mc_;
  BlockMatrix Kb_; // K in 3x3 blocks for the per-step K u~
  std::unique_ptr<StepSolver> solver_;
  std::vector<int> cdofs_;                           // constrained DOFs, in constraint order
  std::vector<int> cset_;                            // constraint index of each
  std::vector<double> camp_;                         // velocity amplitude of each
  Eigen::VectorXd u_, v_, a_, a_prev_, f_, fd_, rc_; // state and forces at t_n
  Eigen::VectorXd ut_, vt_, ku_, b_, f1_, fd1_, a1_, u1_, v1_, rc1_, ac_, tmp_;
  double t_ = 0, e0_ = 0, c_ = 0;
  long n_ = 0;
  double w_ext_ = 0, w_reac_ = 0, w_drag_ = 0;
  double assembly_s_ = 0, setup_s_ = 0;
  int last_iterations_ = 0;
  bool has_loads_ = false, has_drag_ = false;
};

} // namespace lamina::membrane
