#pragma once
/// @file macro_history.hpp
/// @brief A macroscopic loading history of a unit cell: per step, each of
/// the six components (lamina order) is either strain-controlled (E_i
/// given, engineering shear) or stress-controlled (Sigma_i given, Pa).

#include "materials/point_driver.hpp"

#include <array>
#include <vector>

namespace lamina::homogenize {

/// One step of the history.
struct MacroStep {
  double t = 0;                  ///< time at the end of the step (s)
  std::array<double, 6> value{}; ///< E_i or Sigma_i at t, per component
};

/// The whole history (the mask is fixed over it).
struct MacroHistory {
  std::array<bool, 6> stress_controlled{}; ///< true: Sigma_i prescribed, E_i unknown
  std::vector<MacroStep> steps;            ///< t increasing from t_0 = 0 (not listed)
  /// @return the number of stress-controlled components
  int stressComponents() const;
};

/// The paths of `materials drive` as cell loadings (small strain):
/// uniaxial-strain E_xx = rate t; confined E_xx = -rate t; shear
/// E_xy = rate t (engineering), all other strains zero; uniaxial-stress
/// E_xx = rate t with the other five stresses zero; biaxial-stress E_xx =
/// E_yy = rate t with the other four stresses zero. @p steps per leg; with
/// @p unload back to zero at the same rate.
MacroHistory pathHistory(materials::DrivePath path, double rate, double to, int steps, bool unload);

} // namespace lamina::homogenize
