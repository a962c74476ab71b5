#pragma once
/// @file yarn_curve.hpp
/// @brief The stress-strain curve of one yarn direction of a fabric
/// (fabric_law.hpp): a modulus or a piecewise linear table, no compression.
///
/// A curve is the points (e_0 = 0, s_0 = 0), (e_1, s_1) .. (e_n, s_n) with
/// strictly increasing strain and non-decreasing stress, and the slope
/// beyond the last point. Its stress is
///
///     s(e) = 0                                  e <= 0 (a yarn carries no compression)
///     s(e) = s_i + k_i (e - e_i)                e_i <= e < e_{i+1}, k_i = (s_{i+1} - s_i) /
///     (e_{i+1} - e_i) s(e) = s_n + k_n (e - e_n)                e >= e_n (the last slope
///     extrapolated)
///
/// its tangent ds/de is k_i on [e_i, e_{i+1}) (the slope to the right at a
/// point), 0 for e <= 0, and its energy is the exact integral W(e) =
/// int_0^e s: the trapezoids of the whole segments below e plus the part of
/// the segment holding e, s_i (e - e_i) + k_i (e - e_i)^2 / 2. A modulus E
/// is the curve of the single point (0, 0) with last slope E: s(e) = E e
/// exactly for e > 0.
///
/// **CSV** (readYarnCurveCsv): two columns `strain, stress` (strain
/// dimensionless, stress in Pa) separated by a comma or blanks; `#` starts a
/// comment; blank lines are skipped; the first row may be a header (e.g.
/// `strain,stress`), any later row that is not two numbers is an error. The
/// curve must have at least two points, a first strain >= 0 and, where the
/// first strain is 0, a first stress of 0; a table that starts at a
/// positive strain has the point (0, 0) added in front of it (the yarn is
/// unstressed at zero strain). Each violation is a lamina::Error naming the
/// CSV file, its line and the key that names the file.

#include "core/error.hpp"

#include <string>
#include <vector>

namespace lamina::materials {

/// One yarn direction's stress-strain curve (see the file comment).
class YarnCurve {
public:
  /// @return the linear yarn s = @p E e (e > 0): the point (0, 0) and last slope @p E (Pa, > 0)
  static YarnCurve linear(double E);
  /// The curve through @p strain, @p stress (strictly increasing strain from
  /// 0, stress from 0, non-decreasing, finite), extrapolated with the slope of
  /// its last segment. Throws lamina::Error with @p where otherwise (the
  /// message names the offending point, 1-based).
  YarnCurve(std::vector<double> strain, std::vector<double> stress, ErrorContext where = {});

  /// @return the stress s(@p e) (Pa); 0 for e <= 0
  double stress(double e) const;
  /// @return the tangent ds/de at @p e (Pa): the slope of the segment to the right, 0 for e <= 0
  double tangent(double e) const;
  /// @return W(@p e) = int_0^e s (J/m^3), exact for the piecewise linear curve; 0 for e <= 0
  double energy(double e) const;
  /// @return the largest slope of the curve (Pa): the stiffest it responds
  double maxSlope() const { return max_slope_; }
  /// @return the points' strains (the first is 0)
  const std::vector<double>& strains() const { return strain_; }
  /// @return the points' stresses (Pa; the first is 0)
  const std::vector<double>& stresses() const { return stress_; }
  /// @return the slope beyond the last point (Pa)
  double lastSlope() const { return slope_.back(); }

private:
  YarnCurve() = default;
  /// Fills slope_, energy_ (at the points) and max_slope_ from the points and @p last_slope.
  void tabulate(double last_slope);
  /// @return the index i of the segment [e_i, e_{i+1}) holding @p e > 0 (n for e >= e_n)
  std::size_t segment(double e) const;

  std::vector<double> strain_, stress_;
  std::vector<double> slope_;  ///< k_i of segment i; the last is the extrapolation's
  std::vector<double> energy_; ///< W(e_i)
  double max_slope_ = 0;
};

/// Reads the curve of CSV file @p path (see the file comment) named by key
/// @p key; errors name @p path, the line and @p key.
YarnCurve readYarnCurveCsv(const std::string& path, const std::string& key);

} // namespace lamina::materials
