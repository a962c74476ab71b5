#pragma once
/// @file profile.hpp
/// @brief Time profiles of loads and prescribed velocities: a scalar factor
/// f(t) that multiplies a fixed spatial pattern. Loads use the profile's
/// mean over the interval a step stands for (integral(), LoadTime), so a
/// pulse shorter than the step is not missed.

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
  /// @return int f dt over [@p t0, @p t1] (exact: every kind is piecewise
  /// linear), s; what a step that stands for that interval receives
  double integral(double t0, double t1) const;
  /// The shapes a profile takes (key `profile`).
  enum class Kind { Constant, Step, Ramp, Pulse, Table };
  /// @return the shape
  Kind kind() const { return kind_; }

private:
  /// @return an antiderivative of f (F(t1) - F(t0) = integral(t0, t1))
  double primitive(double t) const;
  Kind kind_ = Kind::Constant;
  double t0_ = 0, rise_ = 0, duration_ = 0;
  std::vector<double> tt_, ff_;
  std::vector<double> cum_; ///< table: int f over [tt_.front(), tt_[k]]
};

} // namespace lamina::membrane
