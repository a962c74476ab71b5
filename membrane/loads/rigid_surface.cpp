#include "membrane/loads/rigid_surface.hpp"

#include <algorithm>
#include <cmath>

namespace lamina::membrane {

namespace {

/// A unit vector normal to unit @p a (for a point on an axis, where the
/// radial direction is undefined: any one will do).
Eigen::Vector3d anyNormalTo(const Eigen::Vector3d& a) {
  const Eigen::Vector3d t =
      std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return a.cross(t).normalized();
}

/// The axial coordinate s, the distance r from the axis (c, a) and the
/// radial unit vector of @p x.
struct AxisFrame {
  double s = 0, r = 0;
  Eigen::Vector3d radial;
  AxisFrame(const Eigen::Vector3d& x, const Eigen::Vector3d& c, const Eigen::Vector3d& a) {
    const Eigen::Vector3d d = x - c;
    s = d.dot(a);
    const Eigen::Vector3d p = d - s * a;
    r = p.norm();
    radial = r > 0 ? Eigen::Vector3d(p / r) : anyNormalTo(a);
  }
};

/// The signed distance of the arc's ring: that of the rectangle
/// [-w/2, w/2] x [R - d, R] in the meridional (s, r) half-plane.
Proximity arcProximity(const RigidSurface& g, const Eigen::Vector3d& x) {
  const AxisFrame f(x, g.point, g.axis);
  const double rc = g.radius - 0.5 * g.depth; // the rectangle's centre in r
  const double ss = f.s >= 0 ? 1.0 : -1.0, sr = f.r >= rc ? 1.0 : -1.0;
  const double qs = std::abs(f.s) - 0.5 * g.width, qr = std::abs(f.r - rc) - 0.5 * g.depth;
  Proximity p;
  if (qs > 0 || qr > 0) { // outside: the distance to the nearest face or corner
    const double os = std::max(qs, 0.0), orr = std::max(qr, 0.0);
    p.gap = std::hypot(os, orr);
    p.normal = (ss * os / p.gap) * g.axis + (sr * orr / p.gap) * f.radial;
  } else if (qs > qr) { // inside, nearest a side face
    p.gap = qs;
    p.normal = ss * g.axis;
  } else { // inside, nearest the outer (or inner) face
    p.gap = qr;
    p.normal = sr * f.radial;
  }
  return p;
}

} // namespace

Proximity RigidSurface::proximity(const Eigen::Vector3d& x) const {
  Proximity p;
  switch (shape) {
  case SurfaceShape::Plane:
    p.gap = (x - point).dot(normal);
    p.normal = normal;
    break;
  case SurfaceShape::Sphere: {
    const Eigen::Vector3d d = x - point;
    const double r = d.norm();
    p.gap = r - radius;
    p.normal = r > 0 ? Eigen::Vector3d(d / r) : Eigen::Vector3d::UnitZ();
    break;
  }
  case SurfaceShape::Cylinder: {
    const AxisFrame f(x, point, axis);
    p.gap = f.r - radius;
    p.normal = f.radial;
    break;
  }
  case SurfaceShape::Arc:
    p = arcProximity(*this, x);
    break;
  }
  return p;
}

double RigidSurface::thickness() const {
  switch (shape) {
  case SurfaceShape::Arc:
    return std::min(width, depth);
  case SurfaceShape::Cylinder:
  case SurfaceShape::Sphere:
    return 2 * radius;
  case SurfaceShape::Plane:
    break;
  }
  return std::numeric_limits<double>::infinity();
}

} // namespace lamina::membrane
