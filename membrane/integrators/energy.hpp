#pragma once
/// @file energy.hpp
/// @brief Energy bookkeeping shared by all time integrators.
///
/// Works by the trapezoidal rule over each step,
///   W += (u_{n+1} - u_n).(F_n + F_{n+1}) / 2,
/// for the external loads, the drag, the springs, the damping and the
/// reactions (at constrained DOFs); balance = T + U - E_0 - W. When the
/// model's strain energy is not a potential (tension-only fabric), U is the
/// internal work integrated the same way from U(u_0). For the paper's Newmark scheme (beta1 = beta2
/// = 1/2, alpha = 0) the balance is zero in exact arithmetic.

#include "membrane/integrators/time_integrator.hpp"
#include "membrane/model/constraint.hpp"

namespace lamina::membrane {

/// Energies and works at one time (J).
struct Energy {
  double kinetic = 0;       ///< v.Mv / 2 (M includes M_D: micro-kinetic included)
  double micro_kinetic = 0; ///< v.M_D v / 2, the micro-inertia part of kinetic
  double strain = 0;        ///< u.Ku / 2
  double external_work = 0; ///< work of the loads since t = 0
  double reaction_work = 0; ///< work of the constraint reactions since t = 0
  double drag_work = 0;     ///< work of the drag since t = 0 (<= 0: dissipated)
  double spring_work = 0;   ///< work of the springs to the ground since t = 0
  double damping_work = 0;  ///< work of the mass-proportional damping since t = 0 (<= 0)
  double balance = 0;       ///< E - E0 - W (all works); round-off for the paper's scheme
};

/// The works accumulated over the steps of one run.
struct Works {
  double external = 0; ///< loads (J)
  double reaction = 0; ///< reactions (J)
  double drag = 0;     ///< drag (J)
  double spring = 0;   ///< springs (J)
  double damping = 0;  ///< damping (J)
  double internal = 0; ///< internal force, sum of du.f_int (J; when the scheme keeps f_int)

  /// Adds one step: displacement increment @p du, forces @p f0 at its start
  /// and @p f1 at its end; @p external and @p drag say whether those forces exist.
  void add(const Eigen::VectorXd& du, const StateForces& f0, const StateForces& f1,
           const ConstrainedDofs& cons, bool external, bool drag);
  /// @return the energy record for kinetic @p T, strain @p U and initial energy @p e0
  Energy energy(double T, double U, double e0) const;
};

} // namespace lamina::membrane
