#include "membrane/model/relaxed_wrinkling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lamina::membrane {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The best wrinkle of amplitude w along n(theta) = (cos, sin) for the trial stress St.
struct Trial {
  double theta = 0;
  double f = 0; ///< the energy drop, -(n.St n)^2 / (2 n n : C : n n) when n.St n < 0, else 0
  double r = 0; ///< the stationarity residual m.S n (m = dn/dtheta), S at the unconstrained w
  double w = 0; ///< the unconstrained amplitude -(n.St n) / (n n : C : n n)
  Eigen::Vector3d S = Eigen::Vector3d::Zero(); ///< St + w C (n n)
};

/// @return the wrinkle along @p theta: d f / d theta = 2 w r where w > 0
Trial trialAt(double theta, const Eigen::Vector3d& St, const Eigen::Matrix3d& C) {
  Trial t;
  t.theta = theta;
  const double c = std::cos(theta), s = std::sin(theta);
  const Eigen::Vector3d d(c * c, s * s, 2 * c * s); // n n^T, engineering shear
  const Eigen::Vector3d Cd = C * d;
  const double k = d.dot(Cd), sn = d.dot(St);
  t.w = -sn / k;
  t.f = sn < 0 ? -0.5 * sn * sn / k : 0.0;
  t.S = St + t.w * Cd;
  t.r = c * s * (t.S[1] - t.S[0]) + (c * c - s * s) * t.S[2];
  return t;
}

/// @return the root of r in [a, b] (r(a) < 0 < r(b)) to round-off: false
/// position with the Illinois halving, bisection when it steps outside.
Trial rootOfStationarity(Trial a, Trial b, const Eigen::Vector3d& St, const Eigen::Matrix3d& C) {
  double ra = a.r, rb = b.r; // the (possibly halved) values the secant uses
  int side = 0;
  Trial best = std::abs(a.r) < std::abs(b.r) ? a : b;
  for (int it = 0; it < 200; ++it) {
    const double span = b.theta - a.theta;
    if (!(span > 4 * std::numeric_limits<double>::epsilon() *
                     std::max({std::abs(a.theta), std::abs(b.theta), 1.0})))
      break;
    double x = (a.theta * rb - b.theta * ra) / (rb - ra);
    if (!(x > a.theta && x < b.theta) || it % 8 == 7) // a bisection now and then bounds the count
      x = 0.5 * (a.theta + b.theta);
    const Trial t = trialAt(x, St, C);
    if (std::abs(t.r) < std::abs(best.r))
      best = t;
    if (t.r == 0)
      return t;
    if (t.r < 0) {
      a = t;
      ra = t.r;
      if (side == -1)
        rb *= 0.5;
      side = -1;
    } else {
      b = t;
      rb = t.r;
      if (side == 1)
        ra *= 0.5;
      side = 1;
    }
  }
  return best;
}

/// The samples of the wrinkle direction over [lo, hi] (count + 1 of them) and
/// the root of the stationarity next to the least energy among them; false
/// when r does not change sign from - to + beside it. Keeps only the best
/// sample and its neighbours (no allocation: it runs per element and step).
bool searchDirection(double lo, double hi, int count, const Eigen::Vector3d& St,
                     const Eigen::Matrix3d& C, Trial& out) {
  Trial prev, left, best, right;
  bool has_left = false, has_right = false, pending = false;
  for (int i = 0; i <= count; ++i) {
    const Trial cur = trialAt(lo + (hi - lo) * i / count, St, C);
    if (i == 0 || cur.f < best.f) {
      left = prev;
      has_left = i > 0;
      best = cur;
      has_right = false;
      pending = true;
    } else if (pending) {
      right = cur;
      has_right = true;
      pending = false;
    }
    prev = cur;
  }
  if (best.r == 0) {
    out = best;
    return true;
  }
  if (best.r > 0 && has_left && left.r < 0) {
    out = rootOfStationarity(left, best, St, C);
    return true;
  }
  if (best.r < 0 && has_right && right.r > 0) {
    out = rootOfStationarity(best, right, St, C);
    return true;
  }
  return false;
}

/// @return whether @p t is the KKT point: w > 0 and S = s m m^T with s >= 0
/// (to round-off of the trial stress's size @p scale)
bool isMinimizer(const Trial& t, double scale) {
  return t.w > 0 && t.S[0] + t.S[1] >= -1e-12 * scale && std::abs(t.r) <= 1e-10 * scale;
}

/// The wrinkled state: the direction n of the wrinkles (see the file comment).
Trial wrinkledDirection(const Eigen::Vector3d& St, const Eigen::Matrix3d& C) {
  const double p = 0.5 * (St[0] + St[1]), q = 0.5 * (St[0] - St[1]);
  const double R = std::hypot(q, St[2]), s1 = p + R;
  const double major = 0.5 * std::atan2(St[2], q); // direction of the major principal stress
  const double scale = std::abs(p) + R;
  // The directions in compression, n.St n < 0: an arc (major + delta, major +
  // pi - delta) with r < 0 at its start and > 0 at its end when s1 > 0; all
  // directions otherwise (the window then overlaps itself by a sample at each end).
  double lo = 0, hi = 0;
  int count = 8;
  if (s1 > 0) {
    const double delta = 0.5 * std::acos(std::clamp(-p / R, -1.0, 1.0));
    lo = major + delta;
    hi = major + kPi - delta;
  } else {
    lo = major - kPi / count;
    hi = major + kPi + kPi / count;
    count += 2;
  }
  Trial t;
  if (searchDirection(lo, hi, count, St, C, t) && isMinimizer(t, scale))
    return t;
  // A dense search (the coarse samples missed the basin of the minimum).
  if (s1 <= 0) {
    lo = major - kPi / 512;
    hi = major + kPi + kPi / 512;
  }
  searchDirection(lo, hi, 514, St, C, t);
  return t;
}

} // namespace

RelaxedStress relaxedStress(const Eigen::Vector3d& St, const Eigen::Vector3d& Et,
                            const Eigen::Matrix3d& C) {
  RelaxedStress out;
  if (positiveSemidefinite2(St[0], St[1], St[2])) {
    out.S = St;
    return out;
  }
  if (positiveSemidefinite2(-Et[0], -Et[1], -0.5 * Et[2])) {
    out.state = Wrinkle::Slack;
    out.P = -Et;
    return out; // S = C (Et + P) = 0
  }
  const Trial t = wrinkledDirection(St, C);
  out.state = Wrinkle::Wrinkled;
  out.S = t.S;
  out.w = t.w;
  out.n = {std::cos(t.theta), std::sin(t.theta)};
  out.P = t.w *
          Eigen::Vector3d(out.n.x() * out.n.x(), out.n.y() * out.n.y(), 2 * out.n.x() * out.n.y());
  return out;
}

double relaxedEnergy(const Eigen::Vector3d& E, const Eigen::Matrix3d& C,
                     const Eigen::Vector3d& S0) {
  const Eigen::Vector3d Et = E + C.inverse() * S0;
  const RelaxedStress rs = relaxedStress(C * E + S0, Et, C);
  const Eigen::Vector3d El = E + rs.P;
  return 0.5 * El.dot(C * El) + S0.dot(El);
}

} // namespace lamina::membrane
