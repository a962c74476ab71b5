#pragma once
/// @file profile.hpp
/// @brief Time profiles of loads and prescribed velocities: a scalar factor
/// f(t) that multiplies a fixed spatial pattern.

#include "core/toml_reader.hpp"

#include <string>
#include <vector>

namespace lamina::membrane {

/// f(t) for t >= 0. Kinds: "constant" (1), "step" (0 before t0, then 1),
/// "ramp" (0 before t0, linear to 1 at t0 + rise, then 1), "pulse"
/// (1 on [t0, t0 + duration), else 0), "table" (piecewise linear through
/// (t_k, f_k), held constant outside).
class TimeProfile {
public:
  /// The constant profile f = 1.
  TimeProfile() = default;
  /// Reads `profile` (default "constant") and its keys `t0`, `rise`,
  /// `duration`, `table` from @p r; errors name the file, line and key.
  static TimeProfile read(const core::TableReader& r);
  /// @return f(t)
  double operator()(double t) const;
  /// The shapes a profile takes (key `profile`).
  enum class Kind { Constant, Step, Ramp, Pulse, Table };
  /// @return the shape
  Kind kind() const { return kind_; }

private:
  Kind kind_ = Kind::Constant;
  double t0_ = 0, rise_ = 0, duration_ = 0;
  std::vector<double> tt_, ff_;
};

} // namespace lamina::membrane
