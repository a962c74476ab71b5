#include "membrane/model/profile.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::membrane {

namespace {
/// The case-file names of TimeProfile::Kind (key `profile`).
constexpr auto kProfileKinds =
    core::enumNames<TimeProfile::Kind>({{"constant", TimeProfile::Kind::Constant},
                                        {"step", TimeProfile::Kind::Step},
                                        {"ramp", TimeProfile::Kind::Ramp},
                                        {"pulse", TimeProfile::Kind::Pulse},
                                        {"table", TimeProfile::Kind::Table}});
} // namespace

TimeProfile TimeProfile::read(const core::TableReader& r) {
  TimeProfile p;
  p.kind_ = r.getChoice("profile", kProfileKinds, Kind::Constant);
  if (p.kind_ == Kind::Constant)
    return p;
  if (p.kind_ == Kind::Step) {
    p.t0_ = r.getDouble("t0", 0.0);
  } else if (p.kind_ == Kind::Ramp) {
    p.t0_ = r.getDouble("t0", 0.0);
    p.rise_ = r.getDouble("rise");
    if (!(p.rise_ > 0))
      r.fail("rise", "ramp rise time must be > 0");
  } else if (p.kind_ == Kind::Pulse) {
    p.t0_ = r.getDouble("t0", 0.0);
    p.duration_ = r.getDouble("duration");
    if (!(p.duration_ > 0))
      r.fail("duration", "pulse duration must be > 0");
  } else { // Kind::Table
    const auto m = r.getMatrix("table");
    if (m.empty())
      r.fail("table", "table profile needs at least one [t, f] row");
    for (const auto& row : m) {
      if (row.size() != 2)
        r.fail("table", "each table row must be [t, f]");
      if (!p.tt_.empty() && !(row[0] > p.tt_.back()))
        r.fail("table", "table times must increase strictly");
      p.tt_.push_back(row[0]);
      p.ff_.push_back(row[1]);
      p.cum_.push_back(p.cum_.empty() ? 0.0
                                      : p.cum_.back() + 0.5 * (p.ff_.end()[-2] + row[1]) *
                                                            (row[0] - p.tt_.end()[-2]));
    }
  }
  return p;
}

double TimeProfile::operator()(double t) const {
  if (kind_ == Kind::Constant)
    return 1.0;
  if (kind_ == Kind::Step)
    return t >= t0_ ? 1.0 : 0.0;
  if (kind_ == Kind::Ramp)
    return std::clamp((t - t0_) / rise_, 0.0, 1.0);
  if (kind_ == Kind::Pulse)
    return (t >= t0_ && t < t0_ + duration_) ? 1.0 : 0.0;
  // table
  if (t <= tt_.front())
    return ff_.front();
  if (t >= tt_.back())
    return ff_.back();
  const auto k = static_cast<size_t>(std::upper_bound(tt_.begin(), tt_.end(), t) - tt_.begin());
  const double s = (t - tt_[k - 1]) / (tt_[k] - tt_[k - 1]);
  return ff_[k - 1] + s * (ff_[k] - ff_[k - 1]);
}

double TimeProfile::primitive(double t) const {
  switch (kind_) {
  case Kind::Constant:
    return t;
  case Kind::Step:
    return std::max(0.0, t - t0_);
  case Kind::Ramp: {
    const double s = std::clamp(t - t0_, 0.0, rise_);
    return 0.5 * s * s / rise_ + std::max(0.0, t - t0_ - rise_);
  }
  case Kind::Pulse:
    return std::clamp(t - t0_, 0.0, duration_);
  case Kind::Table:
    break;
  }
  if (t <= tt_.front())
    return ff_.front() * (t - tt_.front());
  if (t >= tt_.back())
    return cum_.back() + ff_.back() * (t - tt_.back());
  const auto k = static_cast<size_t>(std::upper_bound(tt_.begin(), tt_.end(), t) - tt_.begin());
  return cum_[k - 1] + 0.5 * (ff_[k - 1] + (*this)(t)) * (t - tt_[k - 1]);
}

double TimeProfile::integral(double t0, double t1) const {
  return primitive(t1) - primitive(t0);
}

} // namespace lamina::membrane
