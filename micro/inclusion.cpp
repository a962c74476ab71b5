#include "micro/inclusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace lamina::micro {

std::string toString(Shape s) {
  return std::string(kShapeNames.name(s));
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

/// Oblique fiber: visits the copies of the axis line (through centre +
/// lattice translations T, direction A = (u Lx, v Ly, w Lz)) that may pass
/// within sqrt(bound()) of the point d (relative to the centre, nearest
/// image), calling visit(offset) with the offset of d from each (normal to
/// the axis). Every copy crosses the plane x_a = d_a (a: the largest
/// component of A); modulo A the copies are T = n L_a e_a + j L_b e_b +
/// k L_c e_c with 0 <= n < |m_a|. The squared distance Q(o) = |o|^2 -
/// (o.dir)^2 of the in-plane offset o is a convex parabola in o_b for fixed
/// o_c (minimum at o_b* = slope o_c), and Q >= dir_a^2 o_c^2 bounds the k to
/// visit: |m_a| x (a few) copies instead of every copy in a block of cells.
/// bound() is read again after each visit (a shrinking nearest distance).
template <class Bound, class Visit>
void visitFiberCopies(const Eigen::Vector3d& d, const Eigen::Vector3d& dir,
                      const Eigen::Vector3i& m, const Eigen::Vector3d& L, Bound bound,
                      Visit visit) {
  const Eigen::Vector3d A(m[0] * L[0], m[1] * L[1], m[2] * L[2]);
  int a = 0;
  A.cwiseAbs().maxCoeff(&a);
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const double wa2 = dir[a] * dir[a], wb2 = 1 - dir[b] * dir[b];
  const double slope = dir[b] * dir[c] / wb2;
  for (int n = 0; n < std::abs(m[a]); ++n) {
    const double t = (d[a] - n * L[a]) / A[a]; // the copy through n L_a e_a meets x_a = d_a
    const double rb = d[b] - t * A[b], rc = d[c] - t * A[c];
    const double k0 = std::round(rc / L[c]);
    for (int s = 0; wa2 * std::pow(std::max(0.0, s - 0.5) * L[c], 2) <= bound(); ++s)
      for (const int sign : {1, -1}) {
        if (s == 0 && sign < 0)
          continue;
        const double oc = rc - (k0 + sign * s) * L[c];
        Eigen::Vector3d o = Eigen::Vector3d::Zero();
        o[c] = oc;
        o[b] = slope * oc; // the parabola's minimum over o_b
        const double qmin = (o - o.dot(dir) * dir).squaredNorm();
        const double jc = (rb - o[b]) / L[b];
        // j with (1 - dir_b^2) (o_b - o_b*)^2 <= bound - qmin, at least the nearest
        // (no finite bound yet: the nearest j only)
        const double room = bound() - qmin;
        const double half = room < std::numeric_limits<double>::max() / 4
                                ? std::sqrt(std::max(0.0, room) / wb2) / L[b]
                                : 0;
        const double jlo = std::min(std::ceil(jc - half), std::round(jc));
        const double jhi = std::max(std::floor(jc + half), std::round(jc));
        for (double j = jlo; j <= jhi; ++j) {
          o[b] = rb - j * L[b];
          visit(Eigen::Vector3d(o - o.dot(dir) * dir));
        }
      }
  }
}

/// Oblique fiber: the offset of d from the nearest copy of the axis
/// (visitFiberCopies with the nearest distance so far as the bound).
Eigen::Vector3d offsetFromFiber(const Eigen::Vector3d& d, const Eigen::Vector3d& dir,
                                const Eigen::Vector3i& m, const Eigen::Vector3d& L) {
  Eigen::Vector3d best = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  double bestQ = std::numeric_limits<double>::max();
  visitFiberCopies(
      d, dir, m, L, [&] { return bestQ; },
      [&](const Eigen::Vector3d& off) {
        if (off.squaredNorm() < bestQ) {
          bestQ = off.squaredNorm();
          best = off;
        }
      });
  return best;
}

/// Yarn: the nearest point of the centre line x_c = A sin(k x_a) (relative
/// to the centre) to (s, z) in the axis-crimp plane, searched on
/// [s - r, s + r]: Newton on the foot condition
/// g(x) = (s - x) + (z - A sin kx) A k cos kx = 0 from x = s (the foot of a
/// point within the curvature radius, where the squared distance is convex),
/// else the best of a scan of the interval.
/// @return the foot's x_a
double yarnFoot(double A, double k, double s, double z, double r) {
  if (A == 0)
    return s;
  auto dist2 = [&](double x) { return (s - x) * (s - x) + std::pow(z - A * std::sin(k * x), 2); };
  auto newton = [&](double x, double& f) {
    for (int it = 0; it < 20; ++it) {
      const double sn = std::sin(k * x), cs = std::cos(k * x);
      const double g = (s - x) + (z - A * sn) * A * k * cs;
      const double dg = -1 - A * A * k * k * cs * cs - (z - A * sn) * A * k * k * sn;
      if (!(dg < 0))
        return false; // not convex here
      const double xn = std::clamp(x - g / dg, s - r, s + r);
      const double step = std::abs(xn - x);
      x = xn;
      // the distance is stationary at the foot: an error dx in x moves it
      // by O(dx^2), so a step of 1e-9 r (the error after it ~1e-18 r) is
      // far inside round-off of the distance
      if (step <= 1e-9 * r) {
        f = x;
        return true;
      }
    }
    return false;
  };
  double x = s;
  if (newton(s, x))
    return x;
  constexpr int kScan = 16;
  double f = dist2(s);
  x = s;
  for (int i = 0; i <= kScan; ++i) {
    const double xi = s - r + 2 * r * i / kScan;
    const double fi = dist2(xi);
    if (fi < f) {
      x = xi;
      f = fi;
    }
  }
  double xn = x;
  if (newton(x, xn) && dist2(xn) < f)
    return xn;
  return x;
}

/// Layer: the reciprocal vector G = (h/L_x, k/L_y, l/L_z); the slab is where
/// G.(p - centre) lies within thickness/2 |G| of an integer.
Eigen::Vector3d reciprocal(const Eigen::Vector3i& m, const Eigen::Vector3d& L) {
  return Eigen::Vector3d(m[0] / L[0], m[1] / L[1], m[2] / L[2]);
}

} // namespace

YarnFrame yarnFrame(const Inclusion& inc, const Eigen::Vector3d& d) {
  YarnFrame f;
  const int a = inc.axis, c = inc.crimp;
  f.width_axis = 3 - a - c;
  const double A = inc.amplitude, k = 2 * M_PI / inc.wavelength;
  const double s = d[a], z = d[c];
  const double x = yarnFoot(A, k, s, z, 0.5 * inc.thickness);
  const double slope = A * k * std::cos(k * x); // dx_c / dx_a at the foot
  const double norm = std::sqrt(1 + slope * slope);
  f.normal[a] = -slope / norm;
  f.normal[c] = 1 / norm;
  f.u = d[f.width_axis];
  if (A == 0) {
    f.v = z;
  } else {
    // distance to the foot (never below the distance to the centre line),
    // signed by the side of the normal
    const double ra = s - x, rc = z - A * std::sin(k * x);
    const double side = -ra * slope + rc;
    f.v = std::copysign(std::sqrt(ra * ra + rc * rc), side);
  }
  return f;
}

double Inclusion::pathLength(const Eigen::Vector3d& L) const {
  const double periods = L[axis] / wavelength;
  if (amplitude == 0)
    return L[axis];
  // trapezoid rule over one period of sqrt(1 + (A k cos kx)^2): exponentially
  // accurate for a smooth periodic integrand
  constexpr int kPoints = 512;
  const double k = 2 * M_PI / wavelength, Ak = amplitude * k;
  double sum = 0;
  for (int i = 0; i < kPoints; ++i) {
    const double cs = std::cos(2 * M_PI * i / kPoints);
    sum += std::sqrt(1 + Ak * Ak * cs * cs);
  }
  return periods * wavelength * sum / kPoints;
}

double Inclusion::minCurvatureRadius() const {
  if (amplitude == 0)
    return std::numeric_limits<double>::infinity();
  const double k = 2 * M_PI / wavelength;
  return 1 / (amplitude * k * k);
}

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

std::vector<Eigen::Vector3d> Inclusion::axisOffsetsWithin(const Eigen::Vector3d& p, double R,
                                                          const Eigen::Vector3d& L) const {
  const Eigen::Vector3d d = nearestImage(p - center, L);
  std::vector<Eigen::Vector3d> out;
  if (axis >= 0) {
    Eigen::Vector3d off = d;
    off[axis] = 0;
    if (off.squaredNorm() <= R * R)
      out.push_back(off);
    return out;
  }
  visitFiberCopies(
      d, unitDirection(L), lattice, L, [&] { return R * R; },
      [&](const Eigen::Vector3d& off) {
        if (off.squaredNorm() <= R * R)
          out.push_back(off);
      });
  return out;
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
  case Shape::Yarn: {
    // gradient of (u / (w/2))^2 + (v / (t/2))^2 in the tube coordinates
    // (grad u = e_w, grad v = the path normal), scaled by (t/2)^2
    const YarnFrame f = yarnFrame(*this, d);
    const double q = thickness / width;
    Eigen::Vector3d g = f.v * f.normal;
    g[f.width_axis] += f.u * q * q;
    return g.norm() > 0 ? g.normalized() : f.normal;
  }
  }
  return Eigen::Vector3d::UnitX();
}

bool Inclusion::contains(const Eigen::Vector3d& p, const Eigen::Vector3d& L) const {
  return containsOffset(nearestImage(p - center, L), L);
}

bool Inclusion::containsOffset(const Eigen::Vector3d& d, const Eigen::Vector3d& L) const {
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
  case Shape::Yarn: {
    // (u / (w/2))^2 + (v / (t/2))^2 <= 1, written as u^2 (t/w)^2 + v^2 <=
    // (t/2)^2: for w = t and A = 0 the very sum a fibre of radius t/2 tests
    const int w = 3 - axis - crimp;
    const double q = thickness / width, t2 = 0.25 * thickness * thickness;
    const double uu = d[w] * d[w] * (q * q);
    if (uu > t2 || std::abs(d[crimp]) > amplitude + 0.5 * thickness)
      return false; // beyond the width or the crimp band
    if (amplitude > 0) {
      // e: distance to the centre-line point straight along the crimp axis.
      // |v| (the distance to the nearest one) <= e, so uu + e^2 <= (t/2)^2
      // proves inside; inside, the foot lies within |v| of s along the axis,
      // so e <= |v| + A k |v| <= (1 + A k) t/2, and a larger e proves outside.
      const double k = 2 * M_PI / wavelength;
      const double e = std::abs(d[crimp] - amplitude * std::sin(k * d[axis]));
      if (uu + e * e <= t2)
        return true;
      if (e > (1 + amplitude * k) * 0.5 * thickness)
        return false;
    }
    const YarnFrame f = yarnFrame(*this, d);
    return uu + f.v * f.v <= t2;
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
  case Shape::Yarn:
    // a section swept in the normal planes of a plane curve, centroid on the
    // curve, no self-overlap (t/2 below the curvature radius): the section
    // area times the arc length (the first moment int v dA vanishes)
    return M_PI * 0.25 * width * thickness * pathLength(L);
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
  case Shape::Yarn:
    e[axis] = 0.5 * L[axis];
    e[crimp] = amplitude + 0.5 * thickness; // the section tilts: |n_c| <= 1
    e[3 - axis - crimp] = 0.5 * width;
    return e;
  }
  return Eigen::Vector3d::Zero();
}

void Inclusion::scale(double s) {
  semi *= s;
  radius *= s;
  thickness *= s;
  width *= s; // a yarn's centre line (amplitude, wavelength) stays
}

int Inclusion::dimension() const {
  return shape == Shape::Fiber || shape == Shape::Yarn ? 2 : shape == Shape::Layer ? 1 : 3;
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

/// Yarns: whether a point of the surface of @p a lies inside @p b (both
/// already grown), sampled on kYarnSamplesAlong points along the cell
/// length times kYarnSamplesAround around the section. Two solids that
/// intersect have a part of the boundary of one inside the other, so
/// testing both ways finds every overlap deeper than the sampling spacing.
bool yarnSurfaceEnters(const Inclusion& a, const Inclusion& b, const Eigen::Vector3d& L) {
  constexpr int kYarnSamplesAlong = 512, kYarnSamplesAround = 48;
  const int w = 3 - a.axis - a.crimp;
  const double k = 2 * M_PI / a.wavelength;
  for (int i = 0; i < kYarnSamplesAlong; ++i) {
    const double x = L[a.axis] * i / kYarnSamplesAlong;
    const double slope = a.amplitude * k * std::cos(k * x);
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), c = a.center;
    n[a.axis] = -slope;
    n[a.crimp] = 1;
    n /= std::sqrt(1 + slope * slope);
    c[a.axis] += x;
    c[a.crimp] += a.amplitude * std::sin(k * x);
    for (int j = 0; j < kYarnSamplesAround; ++j) {
      const double th = 2 * M_PI * j / kYarnSamplesAround;
      Eigen::Vector3d p = c + 0.5 * a.thickness * std::sin(th) * n;
      p[w] += 0.5 * a.width * std::cos(th);
      if (b.contains(p, L))
        return true;
    }
  }
  return false;
}

/// @return @p y grown by @p g on every side of its section
Inclusion grownYarn(Inclusion y, double g) {
  y.width += 2 * g;
  y.thickness += 2 * g;
  return y;
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
  if (a.shape == Shape::Yarn && b.shape == Shape::Yarn) {
    const Inclusion ga = grownYarn(a, 0.5 * gap), gb = grownYarn(b, 0.5 * gap);
    return yarnSurfaceEnters(ga, gb, L) || yarnSurfaceEnters(gb, ga, L);
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
