#pragma once
/// @file state.hpp
/// @brief The state of the second-order system at one time, and the forces
/// acting on it (second_order_system.hpp): what the time integrators step
/// and what a checkpoint holds.

#include "membrane/loads/contact.hpp"
#include "membrane/model/history.hpp"

#include <Eigen/Dense>

#include <string>

namespace lamina::membrane {

/// Below this many DOFs the vector loops of a step stay on one thread.
inline constexpr int kParallelDofs = 30000;

/// The state of the system at one time: what a checkpoint must hold.
struct State {
  double t = 0;           ///< time (s)
  long step = 0;          ///< steps taken
  Eigen::VectorXd u;      ///< displacements (m), 3 per node
  Eigen::VectorXd v;      ///< velocities (m/s)
  Eigen::VectorXd a;      ///< accelerations (m/s^2)
  SurfaceMotion surfaces; ///< the rigid surfaces' motion (contact.hpp; empty: none)
};

/// Forces acting at one state.
struct StateForces {
  Eigen::VectorXd external; ///< loads F_ext (N, 3 per node)
  Eigen::VectorXd drag;     ///< drag F_drag (N)
  Eigen::VectorXd reaction; ///< R at each constrained DOF, in ConstrainedDofs order (N)
  Eigen::VectorXd spring;   ///< springs to the ground (N; empty: none)
  Eigen::VectorXd damping;  ///< mass-proportional damping -c m v (N; empty: none)
  Eigen::VectorXd internal; ///< internal force f_int (N; empty: not kept by the scheme)
  ContactResult contact;    ///< rigid surfaces' contact forces and sums (empty: none)
};

/// Saves the non-empty members of @p f under "<prefix>external", "<prefix>drag", ...
void saveForces(const std::string& prefix, const StateForces& f, History& h);
/// Restores what saveForces() wrote into @p f, which holds the forces of
/// the same scheme as init() left them: an entry must be present exactly for
/// the members that are non-empty there, with their sizes (a checkpoint is
/// input: a missing, extra or mis-sized entry throws lamina::Error naming it).
void restoreForces(const std::string& prefix, const History& h, StateForces& f);

} // namespace lamina::membrane
