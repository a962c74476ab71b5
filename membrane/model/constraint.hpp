#pragma once
/// @file constraint.hpp
/// @brief Constrained DOF sets: fixed supports and prescribed-velocity strikes.

#include "membrane/model/profile.hpp"

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace lamina::membrane {

/// A set of constrained DOFs moving with prescribed velocity
/// v_dof(t) = amplitude_dof * profile(t) (zero amplitude = fixed).
struct Constraint {
  std::string name;              ///< boundary set name (reactions are summed per set)
  std::vector<int> dofs;         ///< constrained DOFs
  std::vector<double> amplitude; ///< velocity amplitude per DOF (m/s)
  TimeProfile profile;           ///< time factor of the velocity
};

/// The constrained DOFs of all sets, flattened in set order (the order of
/// the reaction vectors).
class ConstrainedDofs {
public:
  ConstrainedDofs() = default;
  /// Flattens @p sets for a model of @p ndof DOFs.
  ConstrainedDofs(const std::vector<Constraint>& sets, int ndof);
  /// @return the number of constrained DOFs
  size_t size() const { return dofs_.size(); }
  /// @return true when nothing is constrained
  bool empty() const { return dofs_.empty(); }
  /// @return the DOFs, in set order
  const std::vector<int>& dofs() const { return dofs_; }
  /// @return the set index of constrained DOF @p k
  int set(size_t k) const { return set_[k]; }
  /// @return the prescribed velocity of constrained DOF @p k at time @p t (m/s)
  double velocity(size_t k, double t) const { return amplitude_[k] * (*sets_)[set_[k]].profile(t); }
  /// @return 1 at constrained DOFs, 0 elsewhere (length ndof)
  const std::vector<char>& mask() const { return mask_; }
  /// Sets the prescribed velocities at time @p t in @p v.
  void prescribe(double t, Eigen::VectorXd& v) const;
  /// @return reactions @p r (one per constrained DOF) summed per set and component
  std::vector<Eigen::Vector3d> sums(const Eigen::VectorXd& r) const;

private:
  const std::vector<Constraint>* sets_ = nullptr;
  std::vector<int> dofs_, set_;
  std::vector<double> amplitude_;
  std::vector<char> mask_;
};

} // namespace lamina::membrane
