#include "membrane/model/fabric_element.hpp"

#include <cmath>

namespace lamina::membrane {

Eigen::Matrix3d planeStressStiffness(const materials::Matrix6& C) {
  // Lamina order: 0 xx, 1 yy, 2 zz, 3 xy, 4 yz, 5 xz.
  constexpr int p[3] = {0, 1, 3};
  Eigen::Matrix3d Cps;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      Cps(i, j) = C(p[i], p[j]) - C(p[i], 2) * C(2, p[j]) / C(2, 2);
  return Cps;
}

FabricElement makeFabricElement(const Mesh& mesh, int e, const Eigen::Vector3d& axis) {
  FabricElement el;
  el.nodes = mesh.triangles[e];
  const Eigen::Vector3d X0 = mesh.point(el.nodes[0]), X1 = mesh.point(el.nodes[1]),
                        X2 = mesh.point(el.nodes[2]);
  const Eigen::Vector3d n = (X1 - X0).cross(X2 - X0);
  el.area0 = 0.5 * n.norm();
  const Eigen::Vector3d e3 = n.normalized();
  Eigen::Vector3d e1 = axis - axis.dot(e3) * e3;
  if (e1.norm() < 1e-6 * axis.norm()) // axis normal to the element: use the first edge
    e1 = X1 - X0;
  e1.normalize();
  const Eigen::Vector3d e2 = e3.cross(e1);
  el.frame.col(0) = e1;
  el.frame.col(1) = e2;
  el.frame.col(2) = e3;
  // Local reference coordinates and the gradients of the linear shape functions.
  std::array<Eigen::Vector2d, 3> xi;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d d = mesh.point(el.nodes[a]) - X0;
    xi[a] = {d.dot(e1), d.dot(e2)};
  }
  const double A2 = 2 * el.area0;
  for (int a = 0; a < 3; ++a) {
    const auto& pj = xi[(a + 1) % 3];
    const auto& pk = xi[(a + 2) % 3];
    el.dN[a] = {(pj.y() - pk.y()) / A2, (pk.x() - pj.x()) / A2};
  }
  return el;
}

Eigen::Vector2d principal2(double a, double b, double c) {
  const double m = 0.5 * (a + b), r = std::hypot(0.5 * (a - b), c);
  return {m + r, m - r};
}

namespace {

/// The projection law: @p st's stress replaced by its tensile part.
void project(FabricStress& st) {
  const double a = st.S[0], b = st.S[1], c = st.S[2];
  const Eigen::Vector2d s = principal2(a, b, c);
  if (s[1] >= 0) {
    st.state = Wrinkle::Taut;
  } else if (s[0] <= 0) {
    st.state = Wrinkle::Slack;
    st.S.setZero();
  } else {
    // Keep s1 n n^T, n the major principal direction.
    st.state = Wrinkle::Wrinkled;
    Eigen::Vector2d n = std::abs(c) > 0 ? Eigen::Vector2d(c, s[0] - a)
                        : a >= b        ? Eigen::Vector2d(1, 0)
                                        : Eigen::Vector2d(0, 1);
    if (std::abs(c) > 0 && n.norm() < 1e-300)
      n = {s[0] - b, c};
    n.normalize();
    st.S = {s[0] * n.x() * n.x(), s[0] * n.y() * n.y(), s[0] * n.x() * n.y()};
  }
}

} // namespace

FabricStress fabricStress(const FabricElement& el, const std::array<Eigen::Vector3d, 3>& x,
                          const Eigen::Matrix3d& Cps, const Eigen::Vector3d& S0,
                          WrinklingLaw wrinkling) {
  FabricStress st;
  st.F.setZero();
  for (int a = 0; a < 3; ++a)
    st.F += x[a] * el.dN[a].transpose();
  const Eigen::Matrix2d C = st.F.transpose() * st.F;
  st.E = {0.5 * (C(0, 0) - 1), 0.5 * (C(1, 1) - 1), C(0, 1)};
  st.S = Cps * st.E + S0;
  if (wrinkling == WrinklingLaw::Projection) {
    project(st);
  } else if (wrinkling == WrinklingLaw::Relaxed &&
             !positiveSemidefinite2(st.S[0], st.S[1], st.S[2])) {
    // E + C^-1 S0: the strain from the stress-free state (C^-1 as LargeDeflection keeps it).
    const Eigen::Matrix3d Cinv = Cps.inverse();
    const RelaxedStress rs = relaxedStress(st.S, st.E + Cinv * S0, Cps);
    st.S = rs.S;
    st.state = rs.state;
  }
  return st;
}

Eigen::Matrix3d fabricForces(const FabricElement& el, const FabricStress& st, double h) {
  Eigen::Matrix2d S;
  S << st.S[0], st.S[2], st.S[2], st.S[1];
  const Eigen::Matrix<double, 3, 2> P = (h * el.area0) * (st.F * S); // h A0 F S
  Eigen::Matrix3d f;
  for (int a = 0; a < 3; ++a)
    f.col(a) = P * el.dN[a];
  return f;
}

double fabricStoredEnergy(const FabricStress& st, const Eigen::Matrix3d& Cinv,
                          const Eigen::Vector3d& S0) {
  return 0.5 * (st.S.dot(Cinv * st.S) - S0.dot(Cinv * S0));
}

Eigen::Vector2d principalCauchy(const FabricStress& st) {
  Eigen::Matrix2d S;
  S << st.S[0], st.S[2], st.S[2], st.S[1];
  const Eigen::Matrix2d C = st.F.transpose() * st.F;
  const double J = std::sqrt(std::max(C.determinant(), 0.0));
  const Eigen::Matrix2d P = S * C;
  // Eigenvalues of S C (similar to C^1/2 S C^1/2, symmetric: real).
  const double tr = P.trace(), det = P.determinant();
  const double r = std::sqrt(std::max(0.25 * tr * tr - det, 0.0));
  if (!(J > 0))
    return Eigen::Vector2d::Zero();
  return {(0.5 * tr + r) / J, (0.5 * tr - r) / J};
}

} // namespace lamina::membrane
