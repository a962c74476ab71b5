#pragma once
/// @file central_difference.hpp
/// @brief Explicit central differences with a lumped mass, stepping a
/// SecondOrderSystem of any structure (the large-deflection fabric, or the
/// linear model).
///
/// One step (t_n = n dt; after a change of step at (t_k, k), t_n = t_k + (n - k) dt),
/// with m the lumped (row-sum) mass:
///   v_{n+1/2} = v_n + dt/2 a_n      (prescribed velocity at t_n + dt/2 on constrained DOFs)
///   u_{n+1}   = u_n + dt v_{n+1/2}
///   m a_{n+1} = F_ext(t_{n+1}, u_{n+1}) + F_drag(u_{n+1}, v_{n+1/2}) + F_s(u_{n+1})
///               + F_c(u_{n+1}, v_{n+1/2}) - c m v_{n+1/2} - f_int(u_{n+1})
///   (the forces of SecondOrderSystem::forces at t_{n+1}, u_{n+1}, v_{n+1/2})
///   v_{n+1}   = v_{n+1/2} + dt/2 a_{n+1}   (prescribed velocity at t_{n+1} on constrained DOFs)
/// Velocity-dependent forces (drag, damping c) use the mid-step velocity
/// (explicit; first order in them, exact at a steady state). The rigid
/// surfaces in contact (F_c, loads/contact.hpp) take the same step: a free
/// body's d_{n+1} = d_n + dt (v_n + dt/2 a_n), its a_{n+1} from the contact
/// forces at t_{n+1}; a prescribed one is at v t_{n+1}. A rigid set
/// takes one acceleration: its total force over its total mass. Reactions
/// R = m a + f_int - F at the constrained DOFs, a = (v_{n+1} - v_n) / dt
/// there. Stable for dt <= the structure's stableStep() (Courant); the
/// default step is safety x that.
///
/// Cost of a step: two threaded passes over the DOF vectors around the force
/// evaluation (v_{n+1/2}, u_{n+1} and the increment; then a_{n+1} and
/// v_{n+1}), serial loops only over the constrained DOFs and rigid sets;
/// the external force and the drag are evaluated only when the case has them
/// (else they stay the zero vectors of init()).

#include "core/error.hpp"
#include "membrane/integrators/time_integrator.hpp"
#include "membrane/system/second_order_system.hpp"

#include <utility>
#include <vector>

namespace lamina::membrane {

/// Central differences on a lumped mass.
class CentralDifference final : public TimeIntegrator {
public:
  /// Steps @p system (which must outlive the scheme) with step @p dt (s).
  CentralDifference(const SecondOrderSystem& system, double dt);
  void init(State& s) override;
  void step(State& s) override;
  double timeStep() const override { return dt_; }
  double timeAt(long step) const override {
    return t_base_ + static_cast<double>(step - step_base_) * dt_;
  }
  /// The step is self-starting (v_n, a_n carry everything): any dt from here on.
  void setTimeStep(double dt, const State& s) override;
  const StateForces& forces() const override { return cur_; }
  const StateForces& previousForces() const override { return prev_; }
  const Eigen::VectorXd& increment() const override { return du_; }
  std::string name() const override {
    return std::string(kIntegratorKindNames.name(IntegratorKind::Explicit));
  }
  /// Saves the forces at t_n and the step "step" = [dt, t_k, k] (the
  /// half-step velocity is recomputed from the State).
  void saveHistory(History& h) const override;
  void restoreHistory(const History& h) override;

private:
  /// The second half of the surfaces' step, once the forces @p f at t_{n+1}
  /// are known: their accelerations and velocities at t_{n+1} into surf1_
  /// (which holds the displacements); @return the count of non-finite values.
  int finishSurfaces(const StateForces& f);
  void accelerate(const StateForces& f, Eigen::VectorXd& a) const;
  /// f.reaction from the accelerations @p a (SecondOrderSystem::reactions).
  void reactions(const Eigen::VectorXd& a, StateForces& f);
  /// The first pass of step(): v_{n+1/2}, u_{n+1}, du from @p s, the
  /// constrained DOFs at their velocity at @p th; @return the count of
  /// non-finite values.
  int drift(const State& s, double th);
  /// The second pass of step() from the forces @p next at @p t1: a_{n+1},
  /// v_{n+1} (rigid sets, constrained DOFs) and the constrained DOFs' m a +
  /// f_int in inertia_; @return the count of non-finite values.
  int kick(const State& s, double t1, const StateForces& next);
  /// @return the places [first, last) in sorted_dof_ of the constrained DOFs in [@p i0, @p i1)
  std::pair<int, int> constrainedIn(int i0, int i1) const;
  /// @return whether place @p c of sorted_dof_ is the first of its DOF (a DOF
  /// in two constraint sets has two adjacent places) in a share starting at @p c0
  bool firstOf(int c, int c0) const;

  const SecondOrderSystem& system_;
  const ConstrainedDofs& cons_;
  double dt_;
  double t_base_ = 0; // time and step of the last change of step (0, 0: none)
  long step_base_ = 0;
  Eigen::VectorXd minv_; // inverse lumped mass (0 on constrained DOFs)
  std::vector<double> rigid_mass_;
  StateForces cur_, prev_;
  Eigen::VectorXd vh_, u1_, v1_, a1_, du_;
  Eigen::VectorXd inertia_;              // m a + f_int at the constrained DOFs
  std::vector<int> by_dof_, sorted_dof_; // the constrained DOFs' k and DOF, by DOF
  SurfaceMotion surf1_;                  // the surfaces at t_{n+1}
  Eigen::VectorXd svh_;                  // and their mid-step velocities
};

} // namespace lamina::membrane
