#pragma once
/// @file load_set.hpp
/// @brief All forces of a model other than the internal (elastic) force,
/// evaluated at a state: the external loads F(t, u) (fixed patterns and
/// follower pressures), the drag F_drag(u, v) and the springs F_s(u).
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
  /// Makes external() give the time-dependent loads' means over
  /// [t - @p dt / 2, t + @p dt / 2] (from 0 at the start; see LoadTime): the
  /// interval a force at t_n stands for in a scheme of step @p dt, so that
  /// every step receives the impulse of its interval and the sum over the
  /// steps is the loads' whole impulse, whatever the step. 0: values at t.
  void setStep(double dt) { half_step_ = 0.5 * dt; }
  /// f = F(t) at displacements @p u (N, length 3 * nodes); each
  /// time-dependent load's mean over the interval setStep() gives.
  void external(double t, const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// f = F_drag at displacements @p u and velocities @p v (N).
  void drag(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& f) const;
  /// f = F_s, the springs' force at displacements @p u (N).
  void springs(const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// @return the springs' force on the structure summed per spring set (N)
  std::vector<Eigen::Vector3d> springSums(const Eigen::VectorXd& u) const;

private:
  void addSurface(WorkKind kind, const LoadTime& when, const Eigen::VectorXd& u,
                  const Eigen::VectorXd& v, Eigen::VectorXd& f) const;
  const Model& model_;
  double half_step_ = 0; ///< half the interval a force stands for (s)
  bool has_external_ = false, has_drag_ = false;
};

} // namespace lamina::membrane
