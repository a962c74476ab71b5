#include "materials/yarn_curve.hpp"

#include "core/pair_table.hpp"

#include "core/format.hpp"
#include "core/input_file.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lamina::materials {

YarnCurve YarnCurve::linear(double E) {
  LAMINA_CHECK(E > 0 && std::isfinite(E), "a yarn modulus must be positive and finite (", E, ")");
  YarnCurve c;
  c.strain_ = {0.0};
  c.stress_ = {0.0};
  c.tabulate(E);
  return c;
}

YarnCurve::YarnCurve(std::vector<double> strain, std::vector<double> stress, ErrorContext where)
    : strain_(std::move(strain)), stress_(std::move(stress)) {
  const auto fail = [&](std::size_t i, const std::string& what) {
    throw Error("point " + std::to_string(i + 1) + " of the stress-strain curve " + what, where);
  };
  if (strain_.size() != stress_.size() || strain_.size() < 2)
    throw Error("a stress-strain curve needs at least two (strain, stress) points", where);
  for (std::size_t i = 0; i < strain_.size(); ++i) {
    if (!std::isfinite(strain_[i]) || !std::isfinite(stress_[i]))
      fail(i, "is not finite");
    if (i == 0 && !(strain_[0] == 0 && stress_[0] == 0))
      fail(i, "must be (0, 0)");
    if (i > 0 && !(strain_[i] > strain_[i - 1]))
      fail(i, "has a strain not above the previous point's (strain must increase strictly)");
    if (i > 0 && !(stress_[i] >= stress_[i - 1]))
      fail(i, "has a stress below the previous point's (the curve must be monotone)");
  }
  const std::size_t n = strain_.size() - 1;
  tabulate((stress_[n] - stress_[n - 1]) / (strain_[n] - strain_[n - 1]));
  if (!(max_slope_ > 0))
    throw Error("the stress-strain curve carries no stress (every point has stress 0)", where);
}

void YarnCurve::tabulate(double last_slope) {
  const std::size_t n = strain_.size();
  slope_.assign(n, last_slope);
  energy_.assign(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double de = strain_[i + 1] - strain_[i];
    slope_[i] = (stress_[i + 1] - stress_[i]) / de;
    energy_[i + 1] = energy_[i] + 0.5 * (stress_[i] + stress_[i + 1]) * de;
  }
  max_slope_ = *std::max_element(slope_.begin(), slope_.end());
}

std::size_t YarnCurve::segment(double e) const {
  const auto hi = std::upper_bound(strain_.begin(), strain_.end(), e); // first point above e
  return static_cast<std::size_t>(hi - strain_.begin()) - 1;           // e > 0 = e_0: >= 0
}

double YarnCurve::stress(double e) const {
  if (!(e > 0))
    return 0.0;
  const std::size_t i = segment(e);
  return stress_[i] + slope_[i] * (e - strain_[i]);
}

double YarnCurve::tangent(double e) const {
  return e > 0 ? slope_[segment(e)] : 0.0;
}

double YarnCurve::energy(double e) const {
  if (!(e > 0))
    return 0.0;
  const std::size_t i = segment(e);
  const double d = e - strain_[i];
  return energy_[i] + stress_[i] * d + 0.5 * slope_[i] * d * d;
}

YarnCurve readYarnCurveCsv(const std::string& path, const std::string& key) {
  const std::string text =
      core::readWholeFile(path, core::kMaxTableBytes, "stress-strain curve", {path, 0, key});
  std::vector<core::PairRow> rows =
      core::readPairRows(text, path, key, "'strain, stress' (strain, Pa)");
  for (const core::PairRow& r : rows)
    if (!std::isfinite(r.first) || !std::isfinite(r.second))
      throw Error("strain and stress must be finite", {path, r.line, key});
  if (rows.size() < 2)
    throw Error("a stress-strain curve needs at least two (strain, stress) rows, found " +
                    std::to_string(rows.size()),
                {path, rows.empty() ? 0 : rows[0].line, key});
  std::vector<double> strain, stress;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const core::PairRow& r = rows[i];
    const ErrorContext at{path, r.line, key};
    if (i == 0 && r.first < 0)
      throw Error("the first strain must be >= 0 (a yarn carries no compression)", at);
    if (i == 0 && r.first == 0 && r.second != 0)
      throw Error("the stress at zero strain must be 0 (the yarn is unstressed at rest), not " +
                      core::formatShort(r.second),
                  at);
    if (i == 0 && r.first > 0) { // the unstressed point (0, 0) in front
      if (r.second < 0)
        throw Error("stress must be >= 0 (the curve rises from (0, 0))", at);
      strain.push_back(0.0);
      stress.push_back(0.0);
    }
    if (i > 0 && !(r.first > rows[i - 1].first))
      throw Error("strain " + core::formatShort(r.first) + " does not increase (line " +
                      std::to_string(rows[i - 1].line) + " has " +
                      core::formatShort(rows[i - 1].first) + ")",
                  at);
    if (i > 0 && !(r.second >= rows[i - 1].second))
      throw Error("stress " + core::formatShort(r.second) + " falls below line " +
                      std::to_string(rows[i - 1].line) + "'s " +
                      core::formatShort(rows[i - 1].second) + " (the curve must be monotone)",
                  at);
    strain.push_back(r.first);
    stress.push_back(r.second);
  }
  return YarnCurve(std::move(strain), std::move(stress), {path, 0, key});
}

} // namespace lamina::materials
