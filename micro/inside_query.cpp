#include "micro/inside_query.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::micro {

InsideQuery::InsideQuery(const Inclusion& inc, const Eigen::Vector3d& L)
    : inc_(inc), L_(L), invL_(L.cwiseInverse()) {
  double sMin = 0, sMax = 0; // the quadratic form's smallest and largest lengths
  switch (inc.shape) {
  case Shape::Sphere:
  case Shape::Ellipsoid:
    M_ = inc.semi.cwiseInverse().asDiagonal() * inc.R.transpose();
    sMin = inc.semi.minCoeff();
    sMax = inc.semi.maxCoeff();
    break;
  case Shape::Fiber:
    if (inc.axis < 0)
      break;
    reads_[inc.axis] = false; // the distance to the axis ignores it
    for (int i = 0; i < 3; ++i)
      if (i != inc.axis)
        M_(i, i) = 1 / inc.radius;
    sMin = sMax = inc.radius;
    break;
  case Shape::Layer:
    if (inc.axis >= 0)
      for (int i = 0; i < 3; ++i)
        reads_[i] = i == inc.axis;
    break;
  case Shape::Yarn:
    break;
  }
  // The round-off of |M d| near the surface is a few ulps times the aspect
  // ratio sMax / sMin (the rotation's cancellation) and the cell over sMin
  // (the offsets' absolute round-off): far below kBoxMargin within these.
  quadratic_ = sMin > 0 && sMax < 1e4 * sMin && L.maxCoeff() < 1e5 * sMin;
  normM_ = quadratic_ ? 1 / sMin : 0;
}

bool InsideQuery::offset(const Eigen::Vector3d& p, const Eigen::Vector3d& half,
                         Eigen::Vector3d& d) const {
  d = p - inc_.center; // as nearestImage(p - center, L)
  for (int i = 0; i < 3; ++i) {
    if (!reads_[i])
      continue;
    const double s = d[i] * invL_[i];
    if (!(std::abs(s) < 1e9))
      return false;
    // nearest integer (halves away from zero, as std::round); within 1e-9
    // of a half, where s and d / L might round apart, the caller falls back
    const double k = static_cast<double>(static_cast<long long>(s < 0 ? s - 0.5 : s + 0.5));
    if (std::abs(s - k) + half[i] * invL_[i] > 0.5 - 1e-9)
      return false;
    d[i] -= L_[i] * k;
  }
  return true;
}

bool InsideQuery::contains(const Eigen::Vector3d& p) const {
  Eigen::Vector3d d;
  if (offset(p, Eigen::Vector3d::Zero(), d))
    return inc_.containsOffset(d, L_);
  return inc_.contains(p, L_);
}

bool InsideQuery::quadraticForm(const Eigen::Vector3d& p, const Eigen::Vector3d& half,
                                Eigen::Vector3d& m0) const {
  Eigen::Vector3d d;
  if (!quadratic_ || !offset(p, half, d))
    return false;
  m0 = M_ * d;
  return true;
}

int InsideQuery::runSide(int i, int j, int k0, int k1, const Eigen::Vector3d& h) const {
  const Eigen::Vector3d half(0.5 * h[0], 0.5 * h[1], 0.5 * (k1 - k0 + 1) * h[2]);
  return boxSide(Eigen::Vector3d(i * h[0], j * h[1], k0 * h[2]) + half, half);
}

int InsideQuery::boxSide(const Eigen::Vector3d& p, const Eigen::Vector3d& half) const {
  Eigen::Vector3d m0;
  if (quadraticForm(p, half, m0)) {
    // |M d| over the box lies within |M| |half| of its value at the centre
    const double rho = m0.norm(), delta = normM_ * half.norm();
    if (rho + delta < 1 - kBoxMargin)
      return 1;
    if (rho - delta > 1 + kBoxMargin)
      return -1;
    return 0;
  }
  Eigen::Vector3d d;
  // (the offsets' round-off, a few ulps of the cell, far below the margin)
  if (inc_.shape != Shape::Yarn || !(inc_.width > 0) || !(L_.maxCoeff() < 1e5 * inc_.thickness) ||
      !offset(p, half, d))
    return 0;
  const int a = inc_.axis, c = inc_.crimp, w = 3 - a - c;
  const double ht = 0.5 * inc_.thickness, q = inc_.thickness / inc_.width;
  const double A = inc_.amplitude;
  const double tol = kBoxMargin * (inc_.thickness + A);
  // every point beyond the width or the crimp band: contains rejects it first
  if (std::max(0.0, std::abs(d[w]) - half[w]) * q > ht + tol ||
      std::max(0.0, std::abs(d[c]) - half[c]) > A + ht + tol)
    return -1;
  // every point within the section around the centre-line point straight
  // along the crimp axis: contains accepts it before the foot search (a
  // straight yarn: that is its test)
  double e = std::abs(d[c]) + half[c];
  if (A > 0) {
    const double k = 2 * M_PI / inc_.wavelength;
    e = std::abs(d[c] - A * std::sin(k * d[a])) + half[c] + A * k * half[a];
  }
  const double u = (std::abs(d[w]) + half[w]) * q;
  return std::sqrt(u * u + e * e) < ht - tol ? 1 : 0;
}

} // namespace lamina::micro
