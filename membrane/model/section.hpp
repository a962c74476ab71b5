#pragma once
/// @file section.hpp
/// @brief The material of one mesh region as the membrane models need it.

#include "materials/stiffness.hpp"

#include <string>

namespace lamina::membrane {

/// Material of one region as the solver needs it.
struct Section {
  std::string name;     ///< region name
  std::string material; ///< where D came from (for the summary)
  materials::Matrix6 D; ///< 6x6 stiffness, lamina order, Pa
  double density = 0;   ///< kg/m^3
  double thickness = 0; ///< m
};

} // namespace lamina::membrane
