#include "membrane/model/law_point.hpp"

#include "core/error.hpp"
#include "materials/kinematics.hpp"
#include "materials/plane_stress.hpp"
#include "membrane/model/fabric_element.hpp"

#include <cmath>

namespace lamina::membrane {

namespace {

using Matrix32 = Eigen::Matrix<double, 3, 2>;
using materials::Vector6;

/// Lamina-order slots of the in-plane components xx, yy, xy.
constexpr int kPlane[3] = {0, 1, 3};

/// @return [F | n], n the unit normal of the deformed element
Eigen::Matrix3d completed(const Matrix32& F) {
  const Eigen::Vector3d n = F.col(0).cross(F.col(1));
  const double a = n.norm();
  LAMINA_CHECK(a > 0 && std::isfinite(a), "the element is degenerate (area ratio ", a, ")");
  Eigen::Matrix3d F3;
  F3 << F, n / a;
  return F3;
}

/// @return U2 = sqrt(F^T F), the in-plane stretch (symmetric positive definite 2 x 2)
Eigen::Matrix2d stretch(const Matrix32& F) {
  const Eigen::Matrix2d C = F.transpose() * F;
  const double s = std::sqrt(C.determinant());
  return (C + s * Eigen::Matrix2d::Identity()) / std::sqrt(C.trace() + 2 * s);
}

/// @return the engineering-strain direction n (x) n of unit in-plane vector @p n
Eigen::Vector3d dyad(const Eigen::Vector2d& n) {
  return {n.x() * n.x(), n.y() * n.y(), 2 * n.x() * n.y()};
}

/// @return the unit eigenvector of the smaller eigenvalue of the symmetric stress [a, c; c, b]
Eigen::Vector2d minorDirection(double a, double b, double c) {
  Eigen::Matrix2d s;
  s << a, c, c, b;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(s);
  return es.eigenvectors().col(0);
}

/// The principal in-plane stresses (major first) of a law-frame stress.
Eigen::Vector2d principal(const Vector6& s) {
  return principal2(s[0], s[1], s[3]);
}

/// The plane-stress step with the wrinkling state it ends in.
struct WrinkledStep {
  materials::PlaneStressResult r;
  Eigen::Vector3d eps_w = Eigen::Vector3d::Zero(); ///< wrinkling strain at t_{n+1}
  Wrinkle state = Wrinkle::Taut;
  double J2 = 1; ///< the law's area ratio (the element's without the wrinkles)
};

/// The area ratio of the material under wrinkling strain @p eps_w, relative to
/// the element's: (2 - tr)/(2 + tr), tr = eps_w,xx + eps_w,yy (the midpoint
/// rule's exp(-tr), exact to third order).
double wrinkledArea(const Eigen::Vector3d& eps_w) {
  const double tr = eps_w[0] + eps_w[1];
  return (2 - tr) / (2 + tr);
}

/// The wrinkled (one free direction) or slack (three) solve. The law's area
/// ratio is the element's less the wrinkles' (the material is not compressed
/// by wrinkling): taken from the wrinkling strain of a first solve, then
/// solved again with it.
void solveWrinkled(const materials::ConstitutiveLaw& law, materials::PlaneStressStep ps,
                   const double* state_n, double* state, WrinkledStep& w) {
  const double J2 = ps.J2;
  for (int pass = 0; pass < 2; ++pass) {
    ps.J2 = J2 * wrinkledArea(w.eps_w);
    w.r = materials::planeStressUpdate(law, ps, state_n, state, false);
    w.J2 = ps.J2; // the area ratio the law was stepped with
    w.eps_w.setZero();
    for (int k = 0; k < ps.n_free; ++k)
      w.eps_w -= w.r.amplitude[static_cast<size_t>(k)] * ps.free_dir[static_cast<size_t>(k)];
  }
}

/// Solves the step, taut first; with @p tension_only, wrinkled or slack when
/// the taut stress has a compressive principal value (see the file comment).
WrinkledStep solve(const materials::ConstitutiveLaw& law, materials::PlaneStressStep ps,
                   bool tension_only, const double* state_n, double* state) {
  WrinkledStep w;
  w.J2 = ps.J2;
  w.r = materials::planeStressUpdate(law, ps, state_n, state, false);
  if (!tension_only || principal(w.r.sigma)[1] >= 0)
    return w;
  if (principal(w.r.sigma)[0] > 0) {
    ps.n_free = 1;
    ps.free_dir[0] = dyad(minorDirection(w.r.sigma[0], w.r.sigma[1], w.r.sigma[3]));
    solveWrinkled(law, ps, state_n, state, w);
    w.state = Wrinkle::Wrinkled;
    if (principal(w.r.sigma)[0] > 0)
      return w;
  }
  ps.n_free = 3;
  ps.free_dir = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  w.eps_w.setZero();
  solveWrinkled(law, ps, state_n, state, w);
  w.state = Wrinkle::Slack;
  return w;
}

} // namespace

double equivalentDeviatoric(const Vector6& d) {
  const double m = (d[0] + d[1] + d[2]) / 3;
  double e2 = 0;
  for (int i = 0; i < 3; ++i)
    e2 += (d[i] - m) * (d[i] - m) + 0.5 * d[3 + i] * d[3 + i]; // 2 (gamma / 2)^2
  return std::sqrt(2.0 / 3.0 * e2);
}

void storeLawPoint(const LawPointEnd& end, double dt, const double* block_n, double* block) {
  using P = LawPoint;
  std::copy(end.F, end.F + 6, block + P::kF);
  std::copy(end.eps, end.eps + 6, block + P::kEps);
  block[P::kLambda3] = end.lambda3;
  std::copy(end.eps_w, end.eps_w + 3, block + P::kWrinkle);
  std::copy(end.sigma, end.sigma + 3, block + P::kSigma);
  block[P::kJ] = end.J;
  block[P::kPsi] = end.psi;
  block[P::kDissipation] = block_n[P::kDissipation] + end.dissipated;
  block[P::kInelastic] = block_n[P::kInelastic] + end.inelastic;
  block[P::kInelasticRate] = dt > 0 ? end.inelastic / dt : 0.0;
  block[P::kWrinkleState] = end.state;
}

void initLawPoint(const materials::ConstitutiveLaw& law, const Matrix32& F0, double* block) {
  std::fill(block, block + LawPoint::size(law), 0.0);
  Eigen::Map<Matrix32>(block + LawPoint::kF) = F0;
  block[LawPoint::kLambda3] = 1;
  block[LawPoint::kJ] = 1;
  law.initState(block + LawPoint::kLaw);
}

Eigen::Vector3d stepLawPoint(const materials::ConstitutiveLaw& law, const Matrix32& F,
                             bool tension_only, double dt, const double* block_n, double* block) {
  using P = LawPoint;
  const Matrix32 F_n = Eigen::Map<const Matrix32>(block_n + P::kF);
  const Eigen::Matrix3d F3 = completed(F);
  const Vector6 deps_geo = materials::rotationFreeIncrement(completed(F_n), F3);
  materials::PlaneStressStep ps;
  ps.eps_n = Eigen::Map<const Vector6>(block_n + P::kEps);
  const Eigen::Map<const Eigen::Vector3d> eps_w_n(block_n + P::kWrinkle);
  for (int i = 0; i < 3; ++i)
    ps.deps_p[i] = deps_geo[kPlane[i]] + eps_w_n[i]; // the previous wrinkles released
  ps.lambda3_n = block_n[P::kLambda3];
  ps.J2_n = block_n[P::kJ] / block_n[P::kLambda3]; // the law's, wrinkles removed
  ps.J2 = F3.determinant();
  ps.dt = dt;
  const WrinkledStep w = solve(law, ps, tension_only, block_n + P::kLaw, block + P::kLaw);
  LAMINA_CHECK(w.r.sigma.allFinite() && std::isfinite(w.r.lambda3) && w.r.lambda3 > 0,
               "the law's stress or thickness stretch is not finite");
  const double J = w.J2 * w.r.lambda3, J_n = block_n[P::kJ];
  // Energy per reference volume: trapezoidal work over the law's strain, stored, dissipated.
  const Vector6 deps = w.r.eps - ps.eps_n;
  Vector6 sigma_n = Vector6::Zero();
  for (int i = 0; i < 3; ++i)
    sigma_n[kPlane[i]] = block_n[P::kSigma + i];
  const double work = 0.5 * (J_n * sigma_n + J * w.r.sigma).dot(deps);
  const double psi = J * law.storedEnergy(w.r.sigma, block + P::kLaw, J);
  // A hyperelastic law stores all its work (law.hpp): no inelastic strain, no
  // dissipation (the trapezoidal work differs from psi - psi_n only by the
  // rule's error, e.g. across a fabric yarn's cut-off).
  const bool elastic = law.isHyperelastic();
  const double inelastic =
      elastic ? 0.0 : equivalentDeviatoric(deps - law.elasticStrain(w.r.sigma - sigma_n, J));
  LawPointEnd end;
  end.F = F.data();
  end.eps = w.r.eps.data();
  end.lambda3 = w.r.lambda3;
  end.eps_w = w.eps_w.data();
  for (int i = 0; i < 3; ++i)
    end.sigma[i] = w.r.sigma[kPlane[i]];
  end.J = J;
  end.psi = psi;
  end.dissipated = elastic ? 0.0 : work - (psi - block_n[P::kPsi]);
  end.inelastic = inelastic;
  end.state = static_cast<double>(static_cast<int>(w.state));
  storeLawPoint(end, dt, block_n, block);
  return lawPointPk2(F, block);
}

Eigen::Vector3d lawPointPk2(const Matrix32& F, const double* block) {
  const Eigen::Matrix2d Uinv = stretch(F).inverse();
  Eigen::Matrix2d s;
  s << block[LawPoint::kSigma], block[LawPoint::kSigma + 2], block[LawPoint::kSigma + 2],
      block[LawPoint::kSigma + 1];
  const Eigen::Matrix2d S = block[LawPoint::kJ] * (Uinv * s * Uinv);
  return {S(0, 0), S(1, 1), 0.5 * (S(0, 1) + S(1, 0))};
}

} // namespace lamina::membrane
