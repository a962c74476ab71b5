#pragma once
/// @file ground_springs.hpp
/// @brief Linear springs from nodes to the ground (the roof's supports):
/// F = -k u on the selected components of each node. Their force is a
/// support reaction: the summary and reactions.csv report it per set.

#include "membrane/loads/surface_load.hpp"

#include <vector>

namespace lamina::membrane {

/// Springs of stiffness k (N/m) on the DOFs of a node set.
class GroundSprings final : public SurfaceLoad {
public:
  /// Springs on @p dofs (3 * node + component), stiffness @p k each.
  GroundSprings(std::string name, std::vector<int> dofs, double k);
  WorkKind kind() const override { return WorkKind::Spring; }
  const std::string& name() const override { return name_; }
  void add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
           const Eigen::VectorXd& v, Eigen::VectorXd& f) const override;
  /// @return the DOFs with a spring
  const std::vector<int>& dofs() const { return dofs_; }
  /// @return the stiffness of each spring (N/m)
  double stiffness() const { return k_; }
  /// @return the force of the springs on the structure, summed (N)
  Eigen::Vector3d sum(const Eigen::VectorXd& u) const;

private:
  std::string name_;
  std::vector<int> dofs_;
  double k_;
};

} // namespace lamina::membrane
