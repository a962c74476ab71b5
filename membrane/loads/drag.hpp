#pragma once
/// @file drag.hpp
/// @brief Aerodynamic drag of the drag paper on the flat (linear) membrane.

#include <Eigen/Dense>

#include <vector>

namespace lamina::membrane {

/// Aerodynamic drag on the nodes of a surface region (drag paper eqs. 1-3):
/// F_i = -1/2 rho_f C_d A_i |V_i| V_n,i n along the normal n = e_z.
struct Drag {
  std::vector<int> nodes;       ///< nodes of the region
  std::vector<double> area;     ///< tributary area of each node in the region (m^2)
  double cd = 1.0;              ///< drag (or pressure) coefficient
  double fluid_density = 1.225; ///< kg/m^3 (air)
  bool resultant = false;       ///< |V| = resultant speed (true) or normal speed (false)
};

/// Adds the drag of @p d at nodal velocities @p v to @p f (drag paper eqs.
/// 1-3 with the normal e_z): 'normal' F = -q |v_n| v_n, 'resultant'
/// F = -q |v|^2 sign(v_n), q = 1/2 rho_f C_d A_i, on the z component.
void addDragForce(const Drag& d, const Eigen::VectorXd& v, Eigen::VectorXd& f);

} // namespace lamina::membrane
