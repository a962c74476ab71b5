#pragma once
/// @file load_set.hpp
/// @brief All forces of a model other than the internal (elastic) force,
/// evaluated at a state: the external loads F(t, u) (fixed patterns and
/// follower pressures), the drag F_drag(u, v), the springs F_s(u) and the
/// rigid surfaces' contact F_c(u, v, surfaces' motion).
///
/// The integrators see the loads only through this class, so a scheme never
/// knows which load kinds a case has. It reads the Model's loads, so it sits
/// with the Model above loads/ (the forces part of the system object).

#include "membrane/system/model.hpp"

#include <Eigen/Dense>

namespace lamina::membrane {

/// The loads of one Model.
class LoadSet {
public:
  /// Keeps a reference to @p model (it must outlive the set).
  explicit LoadSet(const Model& model);
  /// @return true when the model has external loads (else F = 0 always)
  bool hasExternal() const { return has_external_; }
  /// @return true when the model has drag
  bool hasDrag() const { return has_drag_; }
  /// @return true when the model has springs to the ground
  bool hasSprings() const { return !model_.springs.empty(); }
  /// @return true when the model has rigid surfaces in contact
  bool hasContact() const { return !model_.contact.empty(); }
  /// Makes external() give the time-dependent loads' means over
  /// [t - @p dt / 2, t + @p dt / 2] (from 0 at the start; see LoadTime): the
  /// interval a force at t_n stands for in a scheme of step @p dt, so that
  /// every step receives the impulse of its interval and the sum over the
  /// steps is the loads' whole impulse, whatever the step. 0: values at t.
  void setStep(double dt) {
    half_step_ = 0.5 * dt;
    step_ = dt;
  }
  /// The lumped nodal mass per DOF @p m (kg), which the contact's friction
  /// reads (its force never exceeds what stops a node's slip in one step).
  void setLumpedMass(Eigen::VectorXd m) { mass_ = std::move(m); }
  /// f = F(t) at displacements @p u (N, length 3 * nodes); each
  /// time-dependent load's mean over the interval setStep() gives.
  void external(double t, const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// f = F_drag at displacements @p u and velocities @p v (N).
  void drag(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& f) const;
  /// f = F_s, the springs' force at displacements @p u (N).
  void springs(const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// @return the springs' force on the structure summed per spring set (N)
  std::vector<Eigen::Vector3d> springSums(const Eigen::VectorXd& u) const;
  /// The rigid surfaces' contact forces (contact.hpp) at membrane
  /// displacements @p u and velocities @p v, the surfaces' motion being
  /// displacements @p su and velocities @p sv, into @p out.
  void contact(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& su,
               const Eigen::VectorXd& sv, ContactResult& out) const;

private:
  void addSurface(WorkKind kind, const LoadTime& when, const Eigen::VectorXd& u,
                  const Eigen::VectorXd& v, Eigen::VectorXd& f) const;
  const Model& model_;
  double half_step_ = 0; ///< half the interval a force stands for (s)
  double step_ = 0;      ///< the time step (s; 0: not set)
  Eigen::VectorXd mass_; ///< lumped nodal mass per DOF (kg; empty: not set)
  bool has_external_ = false, has_drag_ = false;
};

} // namespace lamina::membrane
