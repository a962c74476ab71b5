#include "micro/inclusion.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::micro {

bool parseShape(const std::string& w, Shape& out) {
  if (w == "sphere")
    out = Shape::Sphere;
  else if (w == "ellipsoid")
    out = Shape::Ellipsoid;
  else if (w == "fiber")
    out = Shape::Fiber;
  else if (w == "layer")
    out = Shape::Layer;
  else
    return false;
  return true;
}

std::string toString(Shape s) {
  switch (s) {
  case Shape::Sphere:
    return "sphere";
  case Shape::Ellipsoid:
    return "ellipsoid";
  case Shape::Fiber:
    return "fiber";
  case Shape::Layer:
    return "layer";
  }
  return "?";
}

Eigen::Vector3d nearestImage(Eigen::Vector3d d, const Eigen::Vector3d& L) {
  for (int i = 0; i < 3; ++i)
    d[i] -= L[i] * std::round(d[i] / L[i]);
  return d;
}

bool Inclusion::contains(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const {
  const Eigen::Vector3d d = nearestImage(p - center, L);
  switch (shape) {
  case Shape::Sphere:
  case Shape::Ellipsoid: {
    const Eigen::Vector3d local = R.transpose() * d;
    return (local.array() / semi.array()).square().sum() <= 1.0;
  }
  case Shape::Fiber: {
    double r2 = 0;
    for (int i = 0; i < 3; ++i)
      if (i != axis)
        r2 += d[i] * d[i];
    return r2 <= radius * radius;
  }
  case Shape::Layer:
    return std::abs(d[axis]) <= 0.5 * thickness;
  }
  return false;
}

double Inclusion::volume(const Eigen::Vector3d& L) const {
  switch (shape) {
  case Shape::Sphere:
  case Shape::Ellipsoid:
    return 4.0 / 3.0 * M_PI * semi.prod();
  case Shape::Fiber:
    return M_PI * radius * radius * L[axis];
  case Shape::Layer:
    return thickness * L.prod() / L[axis];
  }
  return 0;
}

Eigen::Vector3d Inclusion::halfExtent(const Eigen::Vector3d& L) const {
  Eigen::Vector3d e;
  switch (shape) {
  case Shape::Sphere:
  case Shape::Ellipsoid:
    // support function of the rotated ellipsoid along each cell axis
    for (int i = 0; i < 3; ++i)
      e[i] = std::sqrt((R.row(i).transpose().array() * semi.array()).square().sum());
    return e;
  case Shape::Fiber:
    e.setConstant(radius);
    e[axis] = 0.5 * L[axis];
    return e;
  case Shape::Layer:
    e = 0.5 * L;
    e[axis] = 0.5 * thickness;
    return e;
  }
  return Eigen::Vector3d::Zero();
}

void Inclusion::scale(double s) {
  semi *= s;
  radius *= s;
  thickness *= s;
}

int Inclusion::dimension() const {
  return shape == Shape::Fiber ? 2 : shape == Shape::Layer ? 1 : 3;
}

namespace {

bool isEllipsoid(const Inclusion& a) {
  return a.shape == Shape::Sphere || a.shape == Shape::Ellipsoid;
}

/// Perram-Wertheim contact function F(lambda) = lambda (1 - lambda) r^T
/// [(1 - lambda) A^-1 + lambda B^-1]^-1 r; the ellipsoids are disjoint iff
/// max over [0, 1] of F >= 1 (J. Comput. Phys. 58 (1985) 409). F is concave,
/// so a golden-section search finds the maximum.
bool ellipsoidsOverlap(const Inclusion& a, const Inclusion& b, double gap,
                       const Eigen::Vector3d& r) {
  const Eigen::Vector3d sa = a.semi.array() + 0.5 * gap, sb = b.semi.array() + 0.5 * gap;
  const Eigen::Matrix3d Ainv = a.R * sa.array().square().matrix().asDiagonal() * a.R.transpose();
  const Eigen::Matrix3d Binv = b.R * sb.array().square().matrix().asDiagonal() * b.R.transpose();
  auto F = [&](double l) {
    const Eigen::Matrix3d M = (1 - l) * Ainv + l * Binv;
    return l * (1 - l) * r.dot(M.ldlt().solve(r));
  };
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double lo = 0, hi = 1;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = F(x1), f2 = F(x2);
  for (int it = 0; it < 80 && hi - lo > 1e-12; ++it) {
    if (f1 >= 1 || f2 >= 1)
      return false;
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = F(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = F(x1);
    }
  }
  return std::max(f1, f2) < 1;
}

} // namespace

bool overlaps(const Inclusion& a, const Inclusion& b, double gap, const Eigen::Vector3d& L) {
  const Eigen::Vector3d d0 = nearestImage(b.center - a.center, L);
  if (isEllipsoid(a) && isEllipsoid(b)) {
    const double ra = a.semi.maxCoeff() + 0.5 * gap, rb = b.semi.maxCoeff() + 0.5 * gap;
    // every periodic image of b that can come near a
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int k = -1; k <= 1; ++k) {
          const Eigen::Vector3d d = d0 + Eigen::Vector3d(i * L[0], j * L[1], k * L[2]);
          if (d.norm() >= ra + rb)
            continue;
          if (ellipsoidsOverlap(a, b, gap, d))
            return true;
        }
    return false;
  }
  if (a.shape == Shape::Fiber && b.shape == Shape::Fiber) {
    if (a.axis == b.axis) {
      double r2 = 0;
      for (int i = 0; i < 3; ++i)
        if (i != a.axis)
          r2 += d0[i] * d0[i];
      return std::sqrt(r2) < a.radius + b.radius + gap;
    }
    const int c = 3 - a.axis - b.axis; // perpendicular axes: distance along the third
    return std::abs(d0[c]) < a.radius + b.radius + gap;
  }
  // conservative: boxes of half extents (grown by the gap) overlap along every axis
  const Eigen::Vector3d ea = a.halfExtent(L), eb = b.halfExtent(L);
  for (int i = 0; i < 3; ++i)
    if (std::abs(d0[i]) >= ea[i] + eb[i] + gap)
      return false;
  return true;
}

} // namespace lamina::micro
