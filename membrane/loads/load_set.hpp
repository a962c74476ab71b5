#pragma once
/// @file load_set.hpp
/// @brief All forces of a model other than the internal (elastic) force,
/// evaluated at a state: the external loads F(t) and the drag F_drag(v).
///
/// The integrators see the loads only through this class, so a scheme never
/// knows which load kinds a case has.

#include "membrane/model/model.hpp"

#include <Eigen/Dense>

namespace lamina::membrane {

/// The loads of one Model.
class LoadSet {
public:
  /// Keeps a reference to @p model (it must outlive the set).
  explicit LoadSet(const Model& model);
  /// @return true when the model has external loads (else F = 0 always)
  bool hasExternal() const { return !model_.loads.empty(); }
  /// @return true when the model has drag
  bool hasDrag() const { return !model_.drags.empty(); }
  /// f = F(t) at displacements @p u (N, length 3 * nodes).
  void external(double t, const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// f = F_drag at displacements @p u and velocities @p v (N).
  void drag(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& f) const;

private:
  const Model& model_;
};

} // namespace lamina::membrane
