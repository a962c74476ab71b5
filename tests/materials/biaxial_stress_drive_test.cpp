// `materials drive --path biaxial-stress` (F = diag(1 + e, 1 + e, 1 + l_z),
// sigma_zz = 0): for linear isotropic elasticity the biaxial modulus E/(1 -
// nu) times the law's strain, which in finite kinematics is the midpoint sum
// of de / (1 + e) (the Hughes-Winget increments of a diagonal stretch) and
// tends to ln(1 + e) within the midpoint rule's error; in small kinematics
// exactly e. For GVBO, planeStressUpdate driven by the same in-plane
// increments (an implementation that never forms F) reproduces the path.

#include "materials/catalog.hpp"
#include "materials/gvbo_law.hpp"
#include "materials/point_driver.hpp"
#include "plane_stress_point.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace mat = lamina::materials;

namespace {

const double kE = 2.0e9, kNu = 0.3;

std::vector<mat::DriveRow> driveBiaxial(const mat::ConstitutiveLaw& law, mat::Kinematics kin,
                                        double rate, bool unload) {
  mat::DriveOptions o;
  o.path = mat::DrivePath::BiaxialStress;
  o.rate = rate;
  o.to = 0.2;
  o.steps = 200;
  o.unload = unload;
  o.kinematics = kin;
  return mat::drive(law, o);
}

/// Midpoint increment 2 (b - a) / (2 + a + b) of the stretch 1 + a -> 1 + b.
double midpoint(double a, double b) {
  return 2 * (b - a) / (2 + a + b);
}

} // namespace

// Finite kinematics: sigma_xx = sigma_yy = E/(1 - nu) m with m the midpoint
// sum of the driven stretch, and the thickness strain sum -2 nu/(1 - nu) m.
// Error: drive stops at |sigma_zz| <= 1e-10 |sigma_xx| + 1e-6 Pa, which moves
// sigma_xx by nu/(1 - nu) of it: 1e-9 relative (sigma ~ 1e8 Pa) bounds it.
// Against the logarithmic strain: the midpoint rule of int de/(1 + e) with h
// = 1e-3 lies below it by h^2/24 int 2/(1 + e)^3 de = h^2/24 (1 - (1 + e)^-2)
// (the integrand's curvature varies by (1 + h)^3 within a step: 1 % margin).
TEST(BiaxialStressDrive, LinearIsotropicFinite) {
  const mat::LinearElasticLaw law(mat::LawKind::Isotropic, mat::Stiffness::isotropic(kE, kNu));
  const auto rows = driveBiaxial(law, mat::Kinematics::Finite, 1.0, false);
  ASSERT_EQ(rows.size(), 201u);
  double m = 0, mz = 0;
  const double h = 1e-3, Eb = kE / (1 - kNu);
  for (std::size_t n = 1; n < rows.size(); ++n) {
    const mat::DriveRow &r = rows[n], &p = rows[n - 1];
    m += midpoint(p.eps[0], r.eps[0]);
    mz += midpoint(p.eps[2], r.eps[2]);
    EXPECT_EQ(r.eps[0], r.eps[1]);
    EXPECT_NEAR(r.sigma[0], Eb * m, 1e-9 * Eb * m) << n;
    EXPECT_NEAR(r.sigma[1], r.sigma[0], 1e-12 * Eb * m) << n;
    EXPECT_LE(std::abs(r.sigma[2]), 1e-10 * r.sigma[0] + 1e-6) << n;
    EXPECT_NEAR(mz, -2 * kNu / (1 - kNu) * m, 1e-9 * m) << n;
    const double e = r.eps[0], gap = std::log1p(e) - m;
    EXPECT_GE(gap, 0.0) << n;
    EXPECT_LE(gap, 1.01 * h * h / 24 * (1 - 1 / ((1 + e) * (1 + e))) + 1e-15) << n;
  }
  EXPECT_NEAR(rows.back().eps[0], 0.2, 1e-15);
}

// Small kinematics: eps = sym(F - I), so exactly sigma_xx = E/(1 - nu) e and
// eps_zz = -2 nu/(1 - nu) e (same 1e-9 as above for drive's tolerance).
TEST(BiaxialStressDrive, LinearIsotropicSmall) {
  const mat::LinearElasticLaw law(mat::LawKind::Isotropic, mat::Stiffness::isotropic(kE, kNu));
  const auto rows = driveBiaxial(law, mat::Kinematics::Small, 1.0, true);
  ASSERT_EQ(rows.size(), 401u);
  const double Eb = kE / (1 - kNu);
  for (std::size_t n = 1; n < rows.size(); ++n) {
    const double e = rows[n].eps[0];
    const double scale = Eb * std::max(e, 1e-3);
    EXPECT_NEAR(rows[n].sigma[0], Eb * e, 1e-9 * scale) << n;
    EXPECT_NEAR(rows[n].sigma[1], Eb * e, 1e-9 * scale) << n;
    EXPECT_NEAR(rows[n].eps[2], -2 * kNu / (1 - kNu) * e, 1e-9 * std::max(e, 1e-3)) << n;
  }
}

// GVBO (Table 5) at 1e2 /s to 0.2 and back: planeStressUpdate, given the
// in-plane increments of diag(1 + e, 1 + e, 1) by finiteIncrement and the
// area ratio (1 + e)^2, reproduces drive's stress and thickness stretch 1 +
// l_z. Both re-impose sigma_zz = 0 on the total stress every step (errors do
// not add up over steps): drive to 1e-10 of sigma_xx + 1e-6 Pa,
// planeStressUpdate to 1e-12 of max|C| max|eps| (~20 |sigma|, 2e-11 of it),
// each moving sigma_xx by at most about as much: 1e-9 of the history's peak
// stress bounds the difference with a 10x margin.
TEST(BiaxialStressDrive, GvboMatchesPlaneStressUpdate) {
  static const mat::Catalog cat;
  const mat::GvboLaw law(*cat.get("polyurea-gvbo").gvbo);
  const double rate = 1e2;
  const auto rows = driveBiaxial(law, mat::Kinematics::Finite, rate, true);
  ASSERT_EQ(rows.size(), 401u);
  double peak = 0;
  for (const auto& r : rows)
    peak = std::max(peak, r.sigma.cwiseAbs().maxCoeff());
  ASSERT_GT(peak, 1e6); // loaded well beyond the elastic range (A0 = 1 MPa)
  lamina::test::BiaxialPoint pt(law);
  const double dt = 0.2 / rate / 200;
  double worst = 0;
  for (std::size_t n = 1; n < rows.size(); ++n) {
    const mat::PlaneStressResult r = pt.advance(rows[n].eps[0], dt);
    worst = std::max(worst, (r.sigma - rows[n].sigma).cwiseAbs().maxCoeff() / peak);
    EXPECT_NEAR(r.lambda3, 1 + rows[n].eps[2], 1e-9) << n;
  }
  EXPECT_LE(worst, 1e-9);
}
