#include "micro/inclusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

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

namespace {

int gcd3(const Eigen::Vector3i& m) {
  return std::gcd(std::gcd(std::abs(m[0]), std::abs(m[1])), std::abs(m[2]));
}

/// Oblique fiber: the offset from the nearest copy of the axis line (through
/// centre + lattice translations) to the point d (relative to the centre,
/// nearest image). A line through a translation T is the same line as
/// through T + A (A the fiber's lattice vector), so the copies within
/// |u_i|/2 + 1 cells along each axis cover every line that can come within
/// half a cell of d.
Eigen::Vector3d offsetFromFiber(const Eigen::Vector3d& d, const Eigen::Vector3d& dir,
                                const Eigen::Vector3i& m, const Eigen::Vector3d& L) {
  Eigen::Vector3d best = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  const int K0 = std::abs(m[0]) / 2 + 1, K1 = std::abs(m[1]) / 2 + 1, K2 = std::abs(m[2]) / 2 + 1;
  for (int a = -K0; a <= K0; ++a)
    for (int b = -K1; b <= K1; ++b)
      for (int c = -K2; c <= K2; ++c) {
        const Eigen::Vector3d q = d + Eigen::Vector3d(a * L[0], b * L[1], c * L[2]);
        const Eigen::Vector3d perp = q - q.dot(dir) * dir;
        if (perp.squaredNorm() < best.squaredNorm())
          best = perp;
      }
  return best;
}

/// Layer: the reciprocal vector G = (h/L_x, k/L_y, l/L_z); the slab is where
/// G.(p - centre) lies within thickness/2 |G| of an integer.
Eigen::Vector3d reciprocal(const Eigen::Vector3i& m, const Eigen::Vector3d& L) {
  return Eigen::Vector3d(m[0] / L[0], m[1] / L[1], m[2] / L[2]);
}

} // namespace

void Inclusion::setLattice(const Eigen::Vector3i& m) {
  const int g = gcd3(m);
  lattice = m / std::max(g, 1);
  axis = -1;
  for (int i = 0; i < 3; ++i)
    if (lattice.cwiseAbs() == Eigen::Vector3i::Unit(i))
      axis = i;
}

Eigen::Vector3d Inclusion::unitDirection(const Eigen::Vector3d& L) const {
  if (shape == Shape::Layer)
    return reciprocal(lattice, L).normalized();
  return Eigen::Vector3d(lattice[0] * L[0], lattice[1] * L[1], lattice[2] * L[2]).normalized();
}

Eigen::Vector3d Inclusion::axisOffset(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const {
  const Eigen::Vector3d d = nearestImage(p - center, L);
  if (axis < 0)
    return offsetFromFiber(d, unitDirection(L), lattice, L);
  Eigen::Vector3d off = d;
  off[axis] = 0;
  return off;
}

double Inclusion::periodicSpacing(const Eigen::Vector3d& L) const {
  if (shape == Shape::Layer)
    return 1.0 / reciprocal(lattice, L).norm();
  // fiber: the shortest offset between two distinct copies of the axis
  const Eigen::Vector3d dir = unitDirection(L);
  double best = std::numeric_limits<double>::max();
  const int K = lattice.cwiseAbs().maxCoeff() + 1;
  for (int a = -K; a <= K; ++a)
    for (int b = -K; b <= K; ++b)
      for (int c = -K; c <= K; ++c) {
        const Eigen::Vector3d q(a * L[0], b * L[1], c * L[2]);
        const double r = (q - q.dot(dir) * dir).norm();
        if (r > 1e-9 * L.maxCoeff())
          best = std::min(best, r);
      }
  return best;
}

Eigen::Vector3d Inclusion::normalAt(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const {
  const Eigen::Vector3d d = nearestImage(p - center, L);
  switch (shape) {
  case Shape::Sphere:
  case Shape::Ellipsoid: {
    // gradient of |R^T d / semi|^2
    const Eigen::Vector3d local = R.transpose() * d;
    const Eigen::Vector3d g = R * (local.array() / semi.array().square()).matrix();
    return g.norm() > 0 ? g.normalized() : Eigen::Vector3d::UnitX();
  }
  case Shape::Fiber: {
    const Eigen::Vector3d off = offsetFromFiber(d, unitDirection(L), lattice, L);
    return off.norm() > 0 ? off.normalized() : Eigen::Vector3d::UnitX();
  }
  case Shape::Layer: {
    double s = reciprocal(lattice, L).dot(d);
    s -= std::round(s);
    return (s >= 0 ? 1.0 : -1.0) * unitDirection(L);
  }
  }
  return Eigen::Vector3d::UnitX();
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
    if (axis < 0)
      return offsetFromFiber(d, unitDirection(L), lattice, L).squaredNorm() <= radius * radius;
    double r2 = 0;
    for (int i = 0; i < 3; ++i)
      if (i != axis)
        r2 += d[i] * d[i];
    return r2 <= radius * radius;
  }
  case Shape::Layer: {
    if (axis >= 0)
      return std::abs(d[axis]) <= 0.5 * thickness;
    const Eigen::Vector3d G = reciprocal(lattice, L);
    double s = G.dot(d);
    s -= std::round(s);
    return std::abs(s) / G.norm() <= 0.5 * thickness;
  }
  }
  return false;
}

double Inclusion::volume(const Eigen::Vector3d& L) const {
  switch (shape) {
  case Shape::Sphere:
  case Shape::Ellipsoid:
    return 4.0 / 3.0 * M_PI * semi.prod();
  case Shape::Fiber: // the axis crosses the cell once along u L_x e_x + v L_y e_y + w L_z e_z
    return M_PI * radius * radius *
           Eigen::Vector3d(lattice[0] * L[0], lattice[1] * L[1], lattice[2] * L[2]).norm();
  case Shape::Layer: // one slab per plane spacing 1/|G|
    return thickness * L.prod() * reciprocal(lattice, L).norm();
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
    if (axis < 0)
      return 0.5 * L; // an oblique fiber crosses the whole cell
    e.setConstant(radius);
    e[axis] = 0.5 * L[axis];
    return e;
  case Shape::Layer:
    e = 0.5 * L;
    if (axis >= 0)
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
  if (a.shape == Shape::Fiber && b.shape == Shape::Fiber && (a.axis < 0 || b.axis < 0)) {
    if (a.lattice != b.lattice && a.lattice != -b.lattice)
      return true; // crossing oblique fibers: not placed together
    return offsetFromFiber(d0, a.unitDirection(L), a.lattice, L).norm() < a.radius + b.radius + gap;
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
