// The warp-and-fill fabric law (materials/fabric_law.hpp) against its
// definition: a yarn's stress is E eps in tension and 0 in compression, the
// shear is G12 gamma, a tabulated curve reproduces its table and its exact
// integral, the stress is the gradient of the stored energy; under
// `materials drive` and under the membrane's plane-stress step; the catalog's
// roof fabric against the paper's areal weight.
#include "test_support.hpp"

#include "core/toml_reader.hpp"
#include "materials/catalog.hpp"
#include "materials/fabric_law.hpp"
#include "materials/law_spec.hpp"
#include "materials/plane_stress.hpp"
#include "materials/point_driver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mat = lamina::materials;
using mat::Vector6;

namespace {

constexpr double kEw = 641.5e6, kEf = 520.8e6, kG = 28.3e6;

/// The fabric law of moduli kEw, kEf, kG.
mat::FabricLaw linearFabric() {
  mat::FabricParameters p;
  p.warp = mat::YarnCurve::linear(kEw);
  p.fill = mat::YarnCurve::linear(kEf);
  p.G12 = kG;
  return mat::FabricLaw(p);
}

/// One update of @p law at strain @p eps and volume ratio @p J; the tangent in @p T.
Vector6 stressAt(const mat::ConstitutiveLaw& law, const Vector6& eps, double J,
                 mat::Matrix6* T = nullptr) {
  mat::PointStep s;
  s.eps = eps;
  s.J = J;
  double state[1] = {0};
  Vector6 sigma;
  law.update(s, state, state, sigma, T);
  return sigma;
}

Vector6 strain(double xx, double yy, double xy) {
  Vector6 e = Vector6::Zero();
  e << xx, yy, 0, xy, 0, 0;
  return e;
}

} // namespace

// Warp tension: sigma_xx = E_warp eps_xx / J, bit for bit (the yarn is s =
// 0 + E (e - 0)); fill likewise; shear G12 gamma. J = 1.25 shows the
// Kirchhoff stress is the one given by the moduli (sigma = tau / J).
TEST(FabricLaw, TensionAndShearAreTheModuliTimesTheStrain) {
  const mat::FabricLaw law = linearFabric();
  for (const double J : {1.0, 1.25}) {
    mat::Matrix6 T;
    const Vector6 s = stressAt(law, strain(0.012, 0.007, 0.02), J, &T);
    EXPECT_EQ(s[0], kEw * 0.012 / J);
    EXPECT_EQ(s[1], kEf * 0.007 / J);
    EXPECT_EQ(s[3], kG * 0.02 / J);
    EXPECT_EQ(s[2], 0.0);
    EXPECT_EQ(s[4], 0.0);
    EXPECT_EQ(s[5], 0.0);
    EXPECT_EQ(T(0, 0), kEw / J);
    EXPECT_EQ(T(1, 1), kEf / J);
    EXPECT_EQ(T(3, 3), kG / J);
    EXPECT_EQ(T(0, 1), 0.0); // no Poisson coupling
  }
}

// Compression along a yarn: zero stress and zero tangent, in each direction
// alone and in both; the other yarn and the shear are untouched.
TEST(FabricLaw, CompressionAlongAYarnCarriesNothing) {
  const mat::FabricLaw law = linearFabric();
  mat::Matrix6 T;
  Vector6 s = stressAt(law, strain(-0.01, 0.004, 0.0), 1.0, &T);
  EXPECT_EQ(s[0], 0.0);
  EXPECT_EQ(T(0, 0), 0.0);
  EXPECT_EQ(s[1], kEf * 0.004);
  s = stressAt(law, strain(0.003, -0.02, 0.01), 1.0, &T);
  EXPECT_EQ(s[1], 0.0);
  EXPECT_EQ(T(1, 1), 0.0);
  EXPECT_EQ(s[0], kEw * 0.003);
  EXPECT_EQ(s[3], kG * 0.01); // shear is carried either way
  s = stressAt(law, strain(-0.01, -0.02, 0.0), 1.0, &T);
  EXPECT_EQ(s.norm(), 0.0);
  EXPECT_EQ(T(0, 0) + T(1, 1), 0.0);
}

// The tangent is the central difference of the stress (away from the kink
// at zero strain: h = 1e-7 against strains of 1e-2, where the stress is
// linear, so only round-off ~1e-16 E / h ~ 1e-9 E remains; 1e-6 E).
TEST(FabricLaw, TangentIsTheDerivativeOfTheStress) {
  const mat::FabricLaw law = linearFabric();
  for (const Vector6& e : {strain(0.01, 0.02, 0.005), strain(-0.01, 0.02, -0.005)}) {
    mat::PointStep s;
    s.eps = e;
    s.eps[2] = 1e-3;
    s.J = 1.1;
    double state[1] = {0};
    Vector6 sigma;
    mat::Matrix6 T;
    law.update(s, state, state, sigma, &T);
    const mat::Matrix6 N = lamina::test::centralDifferenceTangent(law, s, state, 1e-7);
    EXPECT_LT((T - N).cwiseAbs().maxCoeff(), 1e-6 * kEw);
  }
}

// The stress is the gradient of the stored energy: J sigma = dW/d eps
// (central differences of FabricLaw::energy, 1e-6 relative: W is quadratic
// on each side of the kink, so the difference is exact but for round-off),
// and storedEnergy() after an update is W / J (exactly the state).
TEST(FabricLaw, KirchhoffStressIsTheGradientOfTheStoredEnergy) {
  const mat::FabricLaw law = linearFabric();
  Vector6 e;
  e << 0.02, -0.01, 2e-4, 0.03, -1e-4, 3e-4;
  const double J = 1.05, h = 1e-7;
  mat::PointStep s;
  s.eps = e;
  s.J = J;
  double state[1] = {0};
  Vector6 sigma;
  law.update(s, state, state, sigma, nullptr);
  for (int j = 0; j < 6; ++j) {
    Vector6 p = e, m = e;
    p[j] += h;
    m[j] -= h;
    const double g = (law.energy(p) - law.energy(m)) / (2 * h);
    EXPECT_NEAR(J * sigma[j], g, 1e-6 * kEw * 0.03) << "component " << j;
  }
  const double W = 0.5 * kEw * 0.02 * 0.02 + 0.5 * kG * 0.03 * 0.03 +
                   0.5 * law.parameters().transverseModulus() * (4e-8 + 1e-8 + 9e-8);
  EXPECT_NEAR(law.storedEnergy(sigma, state, J), W / J, 1e-14 * W);
}

// The transverse moduli are kFabricTransverseFraction of the stiffest
// in-plane modulus (the documented choice), and the instantaneous
// stiffness is the diagonal of the steepest slopes.
TEST(FabricLaw, TransverseModuliAreTheDocumentedFraction) {
  const mat::FabricLaw law = linearFabric();
  EXPECT_EQ(law.parameters().transverseModulus(), 1e-3 * kEw);
  const mat::Matrix6 C = law.elasticStiffness(2.0).matrix();
  EXPECT_EQ(C(0, 0), kEw / 2);
  EXPECT_EQ(C(1, 1), kEf / 2);
  EXPECT_EQ(C(3, 3), kG / 2);
  EXPECT_EQ(C(2, 2), 1e-3 * kEw / 2);
  EXPECT_EQ((C - mat::Matrix6(C.diagonal().asDiagonal())).norm(), 0.0);
}

// The membrane's plane-stress step (plane_stress.hpp): the predictor leaves
// nothing to correct, so it converges at once (0 Newton corrections, one
// law update), with eps_zz = 0, lambda3 = 1 exactly, and the in-plane
// stress the fabric's at J = J2 (the thickness does not change).
TEST(FabricLaw, PlaneStressStepConvergesAtOnceWithTheFabricsStress) {
  const mat::FabricLaw law = linearFabric();
  mat::PlaneStressStep ps;
  ps.eps_n = strain(0.004, -0.002, 0.001);
  ps.deps_p = {0.006, -0.001, 0.002};
  ps.J2_n = 1.002;
  ps.J2 = 1.007;
  ps.dt = 1e-5;
  double state[1] = {0};
  const mat::PlaneStressResult r = mat::planeStressUpdate(law, ps, state, state, true);
  EXPECT_LE(r.iterations, 1);
  EXPECT_EQ(r.lambda3, 1.0);
  EXPECT_EQ(r.eps[2], 0.0);
  EXPECT_DOUBLE_EQ(r.sigma[0], kEw * (0.004 + 0.006) / 1.007);
  EXPECT_EQ(r.sigma[1], 0.0); // the fill yarn is in compression: -0.003
  EXPECT_DOUBLE_EQ(r.sigma[3], kG * (0.001 + 0.002) / 1.007);
  EXPECT_NEAR(r.tangent(0, 0), kEw / 1.007, 1e-12 * kEw);
  EXPECT_EQ(r.tangent(1, 1), 0.0);
}

// The law's own plane-stress step (no free direction) is the Newton's
// predictor step and its first test: along a history of in-plane strain
// increments that load and unload both yarns (cut-off included) it must give
// the Newton's eps, lambda3, sigma and state (planeStressUpdate with a
// tangent, which never takes the own step) to the bit (compared with ==, so
// up to the sign of a zero), and planeStressUpdate without a tangent (which
// takes it) the same. A strain of t_n with a transverse part above the
// tolerance is declined, and so is a step with a free direction (both then
// get the Newton), and so is a non-finite stress (the Newton's error).
TEST(FabricLaw, OwnPlaneStressStepIsTheNewtonsToTheBit) {
  const mat::FabricLaw law = linearFabric();
  mat::PlaneStressStep ps;
  double state[1] = {0}, own[1] = {0}, gen[1] = {0};
  double J2 = 1;
  int compressed[2] = {0, 0}; // steps ending with the warp, the fill cut off
  for (int k = 0; k < 200; ++k) {
    const double t = 0.05 * k;
    ps.deps_p = {2e-4 * std::cos(t), -3e-4 * std::sin(1.3 * t), 1e-4 * std::cos(0.7 * t)};
    ps.J2_n = J2;
    ps.J2 = J2 = 1 + 0.01 * std::sin(0.2 * t);
    ps.dt = 1e-6;
    mat::PlaneStressResult a;
    ASSERT_TRUE(law.planeStressStep(ps, state, own, mat::kPlaneStressTolerance, a)) << k;
    const mat::PlaneStressResult b = mat::planeStressUpdate(law, ps, state, gen, true);
    double via[1] = {0};
    const mat::PlaneStressResult c = mat::planeStressUpdate(law, ps, state, via, false);
    ASSERT_EQ(b.iterations, 0) << k;
    ASSERT_TRUE((c.sigma.array() == b.sigma.array()).all() && c.lambda3 == b.lambda3 &&
                via[0] == gen[0])
        << k;
    ASSERT_TRUE((a.eps.array() == b.eps.array()).all()) << k;
    ASSERT_TRUE((a.sigma.array() == b.sigma.array()).all()) << k;
    ASSERT_EQ(a.lambda3, b.lambda3) << k;
    ASSERT_EQ(own[0], gen[0]) << k;
    ps.eps_n = a.eps;
    state[0] = own[0];
    compressed[0] += a.eps[0] < 0;
    compressed[1] += a.eps[1] < 0;
  }
  EXPECT_GT(compressed[0], 10); // both yarns were cut off along the history
  EXPECT_GT(compressed[1], 10);
  mat::PlaneStressResult a;
  mat::PlaneStressStep off = ps;
  off.eps_n[2] = 1e-3; // sigma_zz = E_t 1e-3 / J: far above the tolerance
  EXPECT_FALSE(law.planeStressStep(off, state, own, mat::kPlaneStressTolerance, a));
  EXPECT_EQ(own[0], gen[0]); // nothing written
  mat::PlaneStressStep wrinkled = ps;
  wrinkled.n_free = 1;
  wrinkled.free_dir[0] = {0, 1, 0};
  EXPECT_FALSE(law.planeStressStep(wrinkled, state, own, mat::kPlaneStressTolerance, a));
  mat::PlaneStressStep infinite = ps;
  infinite.deps_p[0] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(law.planeStressStep(infinite, state, own, mat::kPlaneStressTolerance, a));
  EXPECT_THROW(mat::planeStressUpdate(law, infinite, state, own, false), lamina::Error);
}

// `materials drive --path uniaxial-stress` along warp: F = diag(1 + e, 1 +
// l_y, 1 + l_z); with no coupling the lateral stretches stay 1, the law's
// strain is the midpoint sum m = sum 2 (l_k - l_{k-1}) / (l_k + l_{k-1}) of
// the stretch l = 1 + e (kinematics.hpp, exact for a diagonal F) and sigma_xx
// = E_warp m / J with J = l. Computed here from the path alone: agreement
// to 1e-12 of the stress leaves room for round-off of 200 sums only.
TEST(FabricLaw, DriveUniaxialStressAlongWarpIsEWarpTimesTheLogStrainOverJ) {
  const mat::FabricLaw law = linearFabric();
  mat::DriveOptions o;
  o.path = mat::DrivePath::UniaxialStress;
  o.rate = 10.0;
  o.to = 0.15;
  o.steps = 200;
  const auto rows = mat::drive(law, o);
  double m = 0;
  for (std::size_t n = 1; n < rows.size(); ++n) {
    const double l = 1 + rows[n].eps[0], ln = 1 + rows[n - 1].eps[0];
    m += 2 * (l - ln) / (l + ln);
    EXPECT_NEAR(rows[n].sigma[0], kEw * m / l, 1e-12 * kEw * 0.15) << "row " << n;
    EXPECT_NEAR(rows[n].eps[1], 0.0, 1e-12);
    EXPECT_NEAR(rows[n].sigma[1], 0.0, 1e-6);
  }
  EXPECT_NEAR(m, std::log(1.15), 1e-5); // the midpoint sum tends to ln(1 + e)
}

// `materials drive --path confined`: compression along warp, F = diag(1 -
// e, 1, 1): every stress component is zero at every row (the warp yarn
// carries no compression, the others are not strained).
TEST(FabricLaw, DriveConfinedCompressionAlongWarpGivesNoStress) {
  const mat::FabricLaw law = linearFabric();
  mat::DriveOptions o;
  o.path = mat::DrivePath::Confined;
  o.to = 0.1;
  o.steps = 50;
  for (const auto& r : mat::drive(law, o))
    EXPECT_EQ(r.sigma.cwiseAbs().maxCoeff(), 0.0) << "t = " << r.t;
}

// A tabulated curve: (0, 0), (0.01, 1 MPa), (0.03, 5 MPa), (0.05, 6 MPa),
// extrapolated with the last slope 50 MPa. It passes through its points
// exactly, is linear between them, zero below 0; its energy is the sum of
// trapezoids (closed form, typed in here).
TEST(FabricLaw, TabulatedCurveReproducesTheTableAndItsIntegral) {
  const lamina::test::TempDir dir;
  lamina::test::writeFile(dir / "warp.csv", "strain,stress\n0,0\n0.01,1e6\n0.03,5e6\n"
                                            "# the knee\n0.05,6e6\n");
  const mat::YarnCurve c = mat::readYarnCurveCsv((dir / "warp.csv").string(), "warp_curve");
  EXPECT_EQ(c.stress(0.01), 1e6);
  EXPECT_EQ(c.stress(0.03), 5e6);
  EXPECT_EQ(c.stress(0.05), 6e6);
  EXPECT_DOUBLE_EQ(c.stress(0.02), 3e6);
  EXPECT_DOUBLE_EQ(c.stress(0.045), 5.75e6);
  EXPECT_DOUBLE_EQ(c.stress(0.07), 7e6); // 6 MPa + 50 MPa x 0.02
  EXPECT_EQ(c.stress(-0.01), 0.0);
  EXPECT_EQ(c.stress(0.0), 0.0);
  EXPECT_DOUBLE_EQ(c.tangent(0.02), 2e8);
  EXPECT_EQ(c.tangent(-0.02), 0.0);
  EXPECT_DOUBLE_EQ(c.maxSlope(), 2e8);
  // W(0.05) = 0.01 x 1e6 / 2 + 0.02 x 6e6 / 2 + 0.02 x 11e6 / 2 = 5e3 + 6e4 + 1.1e5
  EXPECT_DOUBLE_EQ(c.energy(0.05), 1.75e5);
  // W(0.02) = 5e3 + 0.01 x (1e6 + 3e6) / 2 = 2.5e4
  EXPECT_DOUBLE_EQ(c.energy(0.02), 2.5e4);
  // W(0.07) = 1.75e5 + 0.02 x (6e6 + 7e6) / 2 = 3.05e5
  EXPECT_DOUBLE_EQ(c.energy(0.07), 3.05e5);
  EXPECT_EQ(c.energy(-0.3), 0.0);
}

// A table that starts at a positive strain has (0, 0) added in front.
TEST(FabricLaw, TableStartingAboveZeroStrainGainsTheOrigin) {
  const lamina::test::TempDir dir;
  lamina::test::writeFile(dir / "fill.csv", "0.02 2e6\n0.04 3e6\n");
  const mat::YarnCurve c = mat::readYarnCurveCsv((dir / "fill.csv").string(), "fill_curve");
  ASSERT_EQ(c.strains().size(), 3u);
  EXPECT_EQ(c.strains()[0], 0.0);
  EXPECT_DOUBLE_EQ(c.stress(0.01), 1e6);
  EXPECT_DOUBLE_EQ(c.energy(0.04), 0.5 * 0.02 * 2e6 + 0.5 * 0.02 * 5e6);
}

// The law read from keys (the one reader of catalog entries, cell phases
// and case sections), with a warp curve relative to the file that names
// it and a fill modulus.
TEST(FabricLaw, ReadFromKeysWithACurveRelativeToTheFile) {
  const lamina::test::TempDir dir;
  lamina::test::writeFile(dir / "warp.csv", "0,0\n0.01,1e6\n0.03,5e6\n");
  const toml::table doc = lamina::core::parseTomlString(
      "law = \"fabric\"\nwarp_curve = \"warp.csv\"\nE_fill = 4e8\nG12 = 1e7\nnu12 = 0\n",
      (dir / "fabric.toml").string());
  const lamina::core::TableReader t(doc, (dir / "fabric.toml").string());
  const mat::LawSpec spec = mat::readLawSpec(t);
  ASSERT_EQ(spec.kind, mat::LawKind::Fabric);
  const mat::LawPtr law = spec.make();
  EXPECT_FALSE(law->isLinear());
  EXPECT_TRUE(law->isHyperelastic());
  const Vector6 s = stressAt(*law, strain(0.02, 0.01, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(s[0], 3e6);
  EXPECT_EQ(s[1], 4e8 * 0.01);
  EXPECT_DOUBLE_EQ(spec.C.matrix()(0, 0), 2e8); // the steepest slope of the warp table
}

// The catalog's roof fabric: the paper's 680 g/m^2 (section 5.2) from its
// density and nominal thickness (0.1 %: 1283 kg/m^3 is rounded to 4
// digits), and the derived stiffnesses 340 / 276 kN/m (docs/materials.md).
TEST(FabricLaw, CatalogRoofFabricHasThePapersArealWeight) {
  const mat::Catalog cat(lamina::test::catalogPath());
  const mat::CatalogEntry& e = cat.get("vinyl-coated-polyester");
  ASSERT_EQ(e.law, mat::LawKind::Fabric);
  ASSERT_TRUE(e.nominal_thickness.has_value());
  const double h = *e.nominal_thickness;
  EXPECT_NEAR(e.density * h, 0.680, 1e-3 * 0.680);
  EXPECT_NEAR(e.C.matrix()(0, 0) * h, 340e3, 1e-3 * 340e3);
  EXPECT_NEAR(e.C.matrix()(1, 1) * h, 276e3, 1e-3 * 276e3);
  const mat::LawPtr law = e.makeLaw();
  EXPECT_EQ(law->kind(), mat::LawKind::Fabric);
  EXPECT_EQ(stressAt(*law, strain(-0.01, -0.01, 0.0), 1.0).norm(), 0.0);
}
