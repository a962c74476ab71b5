#pragma once
/// @file load.hpp
/// @brief A fixed load pattern scaled by a time profile (point forces, pressure
/// on the flat membrane, the distributed load of eq. 31, gravity).

#include "membrane/model/profile.hpp"

#include <Eigen/Dense>

#include <string>

namespace lamina::membrane {

/// A load F(t) = profile(t) * pattern.
struct Load {
  std::string name;        ///< for messages and the summary
  Eigen::VectorXd pattern; ///< nodal forces at profile value 1 (N)
  TimeProfile profile;     ///< time factor
};

} // namespace lamina::membrane
