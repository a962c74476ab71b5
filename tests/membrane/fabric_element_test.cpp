// The large-deflection fabric element: S = C_ps E exactly, objectivity,
// tension-only wrinkling, and the plane-stress condensation.
#include "helpers.hpp"
#include "membrane/model/fabric_element.hpp"
#include "membrane/model/large_deflection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

using namespace lamina::membrane;

namespace {

/// One triangle tilted in 3D (a curved roof's element), region "all".
Mesh tiltedTriangle() {
  Mesh m;
  m.source = "test";
  m.nodes = {{0.1, 0.2}, {0.6, 0.3}, {0.2, 0.7}};
  m.z = {0.05, 0.35, -0.2};
  m.triangles = {{0, 1, 2}};
  m.region_of = {0};
  m.regions = {"all"};
  finalizeMesh(m);
  return m;
}

/// Current positions x_a = X_0 + Q U xi_a: the in-plane stretch U applied in
/// the element's own frame Q = [e1 e2], so E = (U^T U - I) / 2 exactly.
std::array<Eigen::Vector3d, 3> stretched(const Mesh& m, const FabricElement& el,
                                         const Eigen::Matrix2d& U) {
  std::array<Eigen::Vector3d, 3> x;
  const Eigen::Vector3d X0 = m.point(el.nodes[0]);
  const Eigen::Matrix<double, 3, 2> Q = el.frame.leftCols<2>();
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector2d xi = Q.transpose() * (m.point(el.nodes[a]) - X0);
    x[a] = X0 + Q * (U * xi);
  }
  return x;
}

/// Isotropic plane stress, written out: E/(1-nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]].
Eigen::Matrix3d isotropicPlaneStress(double E, double nu) {
  Eigen::Matrix3d C;
  C << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
  return E / (1 - nu * nu) * C;
}

const double kE = 5.0e6, kNu = 0.3;

} // namespace

// C_ps = C_pp - C_pz C_zz^-1 C_zp equals the inverse of the in-plane block
// of the compliance when the in-plane and transverse shears do not couple
// (an orthotropic C), and the closed form for an isotropic one. Both are
// independent of the condensation formula; 1e-9 relative is round-off of
// the 6x6 inverse.
TEST(FabricElement, PlaneStressCondensationMatchesTheCompliance) {
  const Eigen::Matrix3d iso =
      planeStressStiffness(lamina::materials::Stiffness::isotropic(kE, kNu).matrix());
  EXPECT_LT((iso - isotropicPlaneStress(kE, kNu)).norm(), 1e-9 * iso.norm());

  lamina::materials::Matrix6 C = lamina::materials::Matrix6::Zero();
  C.topLeftCorner<3, 3>() << 40e9, 3e9, 4e9, 3e9, 10e9, 5e9, 4e9, 5e9, 12e9;
  C(3, 3) = 4e9;
  C(4, 4) = 3e9;
  C(5, 5) = 2e9;
  const Eigen::Matrix<double, 6, 6> S = C.inverse();
  Eigen::Matrix3d Sp;
  const int p[3] = {0, 1, 3};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      Sp(i, j) = S(p[i], p[j]);
  const Eigen::Matrix3d cps = planeStressStiffness(C);
  EXPECT_LT((cps - Sp.inverse()).norm(), 1e-9 * cps.norm());
}

// A tilted 3D element under uniaxial, biaxial and sheared Green-Lagrange
// stretch: E = (U^T U - I)/2 and S = C_ps E to round-off (1e-12 relative:
// a few operations on O(1) numbers).
TEST(FabricElement, SingleElementStressIsCpsTimesGreenLagrangeStrain) {
  const Mesh m = tiltedTriangle();
  const FabricElement el = makeFabricElement(m, 0, Eigen::Vector3d::UnitX());
  const Eigen::Matrix3d cps = isotropicPlaneStress(kE, kNu);
  Eigen::Matrix2d uni, bi, shear;
  uni << 1.2, 0, 0, 1;
  bi << 1.1, 0, 0, 1.3;
  shear << 1.05, 0.2, 0, 0.9;
  for (const Eigen::Matrix2d& U : {uni, bi, shear}) {
    const Eigen::Matrix2d G = 0.5 * (U.transpose() * U - Eigen::Matrix2d::Identity());
    const Eigen::Vector3d E(G(0, 0), G(1, 1), 2 * G(0, 1));
    const FabricStress st =
        fabricStress(el, stretched(m, el, U), cps, Eigen::Vector3d::Zero(), WrinklingLaw::None);
    EXPECT_LT((st.E - E).norm(), 1e-12 * E.norm());
    EXPECT_LT((st.S - cps * E).norm(), 1e-12 * (cps * E).norm());
  }
}

// Objectivity: a rigid rotation R (and translation) of a stretched element
// leaves its strain and stress invariants unchanged and rotates its nodal
// forces by R; a rigid motion of the unstretched element gives zero force.
// Tolerances: round-off relative to the force scale E h L (1e-10).
TEST(FabricElement, RigidRotationLeavesStressUnchangedAndGivesNoForce) {
  const Mesh m = tiltedTriangle();
  const FabricElement el = makeFabricElement(m, 0, Eigen::Vector3d::UnitX());
  const Eigen::Matrix3d cps = isotropicPlaneStress(kE, kNu);
  const double h = 1e-3, scale = kE * h * 0.5;
  Eigen::Matrix2d U;
  U << 1.15, 0.1, 0.0, 0.95;
  const auto x = stretched(m, el, U);
  const FabricStress st = fabricStress(el, x, cps, Eigen::Vector3d::Zero(), WrinklingLaw::None);
  const Eigen::Matrix3d f = fabricForces(el, st, h);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -0.8, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d c(4.0, -2.0, 7.5);
  std::array<Eigen::Vector3d, 3> xr, rigid;
  for (int a = 0; a < 3; ++a) {
    xr[a] = R * x[a] + c;
    rigid[a] = R * m.point(el.nodes[a]) + c;
  }
  const FabricStress sr = fabricStress(el, xr, cps, Eigen::Vector3d::Zero(), WrinklingLaw::None);
  EXPECT_NEAR(sr.S[0] + sr.S[1], st.S[0] + st.S[1], 1e-10 * kE);
  EXPECT_NEAR(sr.S[0] * sr.S[1] - sr.S[2] * sr.S[2], st.S[0] * st.S[1] - st.S[2] * st.S[2],
              1e-10 * kE * kE);
  EXPECT_LT((fabricForces(el, sr, h) - R * f).norm(), 1e-10 * scale);
  const FabricStress s0 = fabricStress(el, rigid, cps, Eigen::Vector3d::Zero(), WrinklingLaw::None);
  EXPECT_LT(fabricForces(el, s0, h).norm(), 1e-10 * scale);
  EXPECT_GT(f.norm(), 1e-3 * scale); // the stretched one does carry force
}

// The projection wrinkling law (wrinkling = "projection"), by hand: E = [0.05, -0.05, 0] gives S11
// = c (0.05 - 0.3 x 0.05) > 0 and S22 = c (-0.05 + 0.3 x 0.05) < 0: wrinkled, S = [S11, 0, 0];
// biaxial compression gives no stress (slack); a sheared state keeps only its
// tensile principal part (principal values >= 0, the major one unchanged).
TEST(FabricElement, TensionOnlyCarriesNoCompression) {
  const Mesh m = tiltedTriangle();
  const FabricElement el = makeFabricElement(m, 0, Eigen::Vector3d::UnitX());
  const Eigen::Matrix3d cps = isotropicPlaneStress(kE, kNu);
  const double c = kE / (1 - kNu * kNu);
  Eigen::Matrix2d U;
  U << std::sqrt(1.1), 0, 0, std::sqrt(0.9); // E11 = 0.05, E22 = -0.05
  FabricStress st =
      fabricStress(el, stretched(m, el, U), cps, Eigen::Vector3d::Zero(), WrinklingLaw::Projection);
  EXPECT_EQ(st.state, Wrinkle::Wrinkled);
  EXPECT_NEAR(st.S[0], c * (0.05 - kNu * 0.05), 1e-9 * c);
  EXPECT_NEAR(st.S[1], 0.0, 1e-9 * c);
  EXPECT_NEAR(st.S[2], 0.0, 1e-9 * c);

  U << 0.9, 0, 0, 0.95;
  st =
      fabricStress(el, stretched(m, el, U), cps, Eigen::Vector3d::Zero(), WrinklingLaw::Projection);
  EXPECT_EQ(st.state, Wrinkle::Slack);
  EXPECT_EQ(st.S.norm(), 0.0);
  EXPECT_EQ(fabricForces(el, st, 1e-3).norm(), 0.0);

  U << 1.05, 0.3, 0, 0.8;
  const FabricStress full =
      fabricStress(el, stretched(m, el, U), cps, Eigen::Vector3d::Zero(), WrinklingLaw::None);
  st =
      fabricStress(el, stretched(m, el, U), cps, Eigen::Vector3d::Zero(), WrinklingLaw::Projection);
  const Eigen::Vector2d pf = principal2(full.S[0], full.S[1], full.S[2]);
  const Eigen::Vector2d pt = principal2(st.S[0], st.S[1], st.S[2]);
  ASSERT_LT(pf[1], 0.0);
  ASSERT_GT(pf[0], 0.0);
  EXPECT_NEAR(pt[0], pf[0], 1e-9 * c);
  EXPECT_NEAR(pt[1], 0.0, 1e-9 * c);
  EXPECT_GE(principalCauchy(st)[1], -1e-9 * c);
}

// A fabric membrane compressed in-plane (u = -0.1 x, edges and all) carries
// no compressive stress anywhere: every element slack, zero internal force.
TEST(FabricElement, CompressedMembraneIsSlackEverywhere) {
  Model m = test::modelFromText(R"(
model = "large_deflection"
[mesh]
Lx = 1.0
nx = 4
[[section]]
E = 5.0e6
nu = 0.3
density = 1000.0
thickness = 1.0e-3
tension_only = true
[time]
t_end = 1.0e-3
)");
  LargeDeflection s(m);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.numDofs());
  for (int i = 0; i < m.mesh.numNodes(); ++i)
    u[3 * i] = -0.1 * m.mesh.nodes[i].x();
  Eigen::VectorXd f;
  s.internalForce(u, f);
  EXPECT_EQ(f.norm(), 0.0);
  for (const auto& c : s.cellFields(u)) {
    if (c.name == "wrinkled") {
      for (double w : c.values)
        EXPECT_EQ(w, 2.0);
    } else if (c.name == "principal_stress") {
      for (double v : c.values)
        EXPECT_EQ(v, 0.0);
    }
  }
}

// Material axis per region: the reference vector is projected onto the
// tilted element, so stretching the element along that projection loads the
// material's x direction (S11 = C11 E11) and across it the y direction
// (S22 = C22 E22) of an orthotropic fabric (warp 4x stiffer than weft).
// The axis vector has a component along the normal, which must not matter.
TEST(FabricElement, MaterialAxisIsTheProjectedReferenceVector) {
  const Mesh m = tiltedTriangle();
  Eigen::Matrix3d cps;
  cps << 4e6, 0.3e6, 0, 0.3e6, 1e6, 0, 0, 0, 0.2e6;
  const Eigen::Vector3d n = (m.point(1) - m.point(0)).cross(m.point(2) - m.point(0)).normalized();
  const Eigen::Vector3d d = (m.point(2) - m.point(0)).normalized(); // an in-plane direction
  const FabricElement el = makeFabricElement(m, 0, d + 0.7 * n);
  EXPECT_LT((el.frame.col(0) - d).norm(), 1e-12);
  // Stretch by 1.1 along d only: x_a = X_a + 0.1 (d . (X_a - X_0)) d.
  std::array<Eigen::Vector3d, 3> x;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d X = m.point(el.nodes[a]);
    x[a] = X + 0.1 * d.dot(X - m.point(el.nodes[0])) * d;
  }
  const FabricStress st = fabricStress(el, x, cps, Eigen::Vector3d::Zero(), WrinklingLaw::None);
  const double E11 = 0.5 * (1.1 * 1.1 - 1);
  EXPECT_NEAR(st.E[0], E11, 1e-12);
  EXPECT_NEAR(st.E[1], 0.0, 1e-12);
  EXPECT_NEAR(st.S[0], 4e6 * E11, 1e-6);
  EXPECT_NEAR(st.S[1], 0.3e6 * E11, 1e-6);
}
