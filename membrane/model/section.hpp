#pragma once
/// @file section.hpp
/// @brief The material of one mesh region as the membrane models need it.

#include "materials/stiffness.hpp"

#include <Eigen/Dense>

#include <limits>
#include <string>

namespace lamina::membrane {

/// Material of one region as the solver needs it.
struct Section {
  std::string name;     ///< region name
  std::string material; ///< where D came from (for the summary)
  materials::Matrix6 D; ///< 6x6 stiffness, lamina order, Pa
  double density = 0;   ///< kg/m^3
  double thickness = 0; ///< m
  // Large-deflection model only (model = "large_deflection"):
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();     ///< reference direction of the material x
                                                       ///< axis, projected onto each element
  Eigen::Vector3d prestress = Eigen::Vector3d::Zero(); ///< in-plane tension [T11, T22, T12]
                                                       ///< in material axes (N/m)
  bool tension_only = false; ///< no compressive principal stress (wrinkling)
  double failure_strain = std::numeric_limits<double>::infinity(); ///< max principal
                                                                   ///< Green-Lagrange strain
  double failure_stress = std::numeric_limits<double>::infinity(); ///< max principal Cauchy
                                                                   ///< stress (Pa)
  /// Micro-inertia (GVBO chapter eq. 35, sigma-bar = sigma + zeta^2 D eps''):
  /// zeta^2 D, 6x6, lamina order, kg/m; zero = none. It adds the gradient
  /// inertia h A B^T (zeta^2 D) B of each element to the mass.
  materials::Matrix6 dispersion = materials::Matrix6::Zero();
  /// @return whether the section carries micro-inertia
  bool hasMicroInertia() const { return dispersion.cwiseAbs().maxCoeff() > 0; }
};

} // namespace lamina::membrane
