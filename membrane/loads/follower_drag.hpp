#pragma once
/// @file follower_drag.hpp
/// @brief The drag of the drag paper (eqs. 1-3) on the deformed surface: at
/// node i of the region, with the current tributary area A_i (a third of
/// each adjacent current triangle) and the current nodal normal n_i (the
/// normalized sum of the adjacent triangles' area vectors),
///   'normal':    F_i = - 1/2 rho_f C_d A_i |v_n| v_n n_i,      v_n = v_i . n_i
///   'resultant': F_i = - 1/2 rho_f C_d A_i |v_i|^2 sign(v_n) n_i.
/// The force is along the normal (fluid pressure is normal to the surface),
/// opposite to the normal motion.

#include "membrane/loads/surface_load.hpp"

#include <vector>

namespace lamina::membrane {

/// Follower drag on a set of elements.
class FollowerDrag final : public SurfaceLoad {
public:
  /// Drag on @p elements with coefficient @p cd, fluid density @p rho (kg/m^3).
  FollowerDrag(std::string name, std::vector<int> elements, double cd, double rho, bool resultant);
  WorkKind kind() const override { return WorkKind::Drag; }
  const std::string& name() const override { return name_; }
  void add(const LoadTime& when, const Mesh& mesh, const Eigen::VectorXd& u,
           const Eigen::VectorXd& v, Eigen::VectorXd& f) const override;

private:
  std::string name_;
  std::vector<int> elements_, nodes_;
  double cd_, rho_;
  bool resultant_;
};

} // namespace lamina::membrane
