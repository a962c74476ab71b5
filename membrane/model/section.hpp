#pragma once
/// @file section.hpp
/// @brief The material of one mesh region as the membrane models need it.

#include "core/enum_names.hpp"
#include "materials/law.hpp"
#include "materials/stiffness.hpp"

#include <Eigen/Dense>

#include <limits>
#include <string>

namespace lamina::membrane {

/// The wrinkling law of a tension-only section with a linear law (fabric_element.hpp).
enum class WrinklingLaw : int {
  None = 0,       ///< not tension-only: S = C_ps E + S0
  Relaxed = 1,    ///< tension-field relaxed energy (conservative)
  Projection = 2, ///< tensile part of the trial stress (not conservative)
};

/// The names of the section key `wrinkling` (None is `tension_only = false`).
inline constexpr auto kWrinklingLawNames = core::enumNames<WrinklingLaw>(
    {{"relaxed", WrinklingLaw::Relaxed}, {"projection", WrinklingLaw::Projection}});

/// Material of one region as the solver needs it.
///
/// A section holds a constitutive law (materials/law.hpp). A linear law (or
/// none, in a model built by hand) is its stiffness D, and the models keep
/// their fast paths for it: the linear membrane assembles K from D, the
/// large-deflection membrane computes S = C_ps E from D. A nonlinear law
/// (GVBO, a reduced-order cell) is stepped at every element with its own
/// state (large-deflection model only); D is then its instantaneous
/// stiffness at rest, law->elasticStiffness(1), for the summary.
struct Section {
  std::string name;      ///< region name
  std::string material;  ///< where the law came from (for the summary)
  materials::LawPtr law; ///< the law; nullptr: linear elastic with D
  materials::Matrix6 D;  ///< 6x6 stiffness, lamina order, Pa (see above)
  double density = 0;    ///< kg/m^3
  double thickness = 0;  ///< m
  // Large-deflection model only (model = "large_deflection"):
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();     ///< reference direction of the material x
                                                       ///< axis, projected onto each element
  Eigen::Vector3d prestress = Eigen::Vector3d::Zero(); ///< in-plane tension [T11, T22, T12]
                                                       ///< in material axes (N/m)
  bool tension_only = false; ///< no compressive principal stress (wrinkling)
  /// The wrinkling law of a tension-only section with a linear law (a
  /// nonlinear law wrinkles by its stress-free wrinkling strain, law_point.hpp)
  WrinklingLaw wrinkling = WrinklingLaw::Relaxed;
  double failure_strain = std::numeric_limits<double>::infinity(); ///< max principal
                                                                   ///< Green-Lagrange strain
  double failure_stress = std::numeric_limits<double>::infinity(); ///< max principal Cauchy
                                                                   ///< stress (Pa)
  /// Micro-inertia (GVBO chapter eq. 35, sigma-bar = sigma + zeta^2 D eps''):
  /// zeta^2 D, 6x6, lamina order, kg/m; zero = none. It adds the gradient
  /// inertia h A B^T (zeta^2 D) B of each element to the mass.
  materials::Matrix6 dispersion = materials::Matrix6::Zero();
  /// @return true when the section is linear elastic with D (no law, or a linear one)
  bool isLinear() const { return !law || law->isLinear(); }
  /// @return the wrinkling law of the linear fast path: None unless tension_only
  WrinklingLaw wrinklingLaw() const { return tension_only ? wrinkling : WrinklingLaw::None; }
  /// @return whether the section carries micro-inertia
  bool hasMicroInertia() const { return dispersion.cwiseAbs().maxCoeff() > 0; }
};

} // namespace lamina::membrane
