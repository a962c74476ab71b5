// The stiffness type against outside numbers: the membrane paper's eq. (16)
// written out by hand, textbook isotropic relations, the fourth-order tensor
// rotation rule, symmetry invariances, the cubic anisotropy-index formula,
// Voigt >= Reuss bounds, and Table 1 of the membrane paper from the catalog.

#include "core/error.hpp"
#include "materials/catalog.hpp"
#include "materials/conversions.hpp"
#include "materials/symmetry.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mat = lamina::materials;
using lamina::test::errorOf;
using lamina::test::randomRotation;
using lamina::test::randomSpd;
using lamina::test::relDiff;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double GPa = 1e9;

mat::Matrix6 table1() {
  return lamina::test::membranePaperTable1();
}

const mat::Catalog& catalog() {
  static const mat::Catalog cat(lamina::test::catalogPath());
  return cat;
}

} // namespace

// ---------------------------------------------------------------- isotropic

// Membrane paper eq. (16): D = [D1 0; 0 D2], D1 = E/((1+nu)(1-2nu)) *
// [[1-nu, nu, nu], [nu, 1-nu, nu], [nu, nu, 1-nu]], D2 = E/((1+nu)(1-2nu)) *
// (1-2nu)/2 * I. Both sides take about six roundings per entry: 2e-15
// relative (about 9 ulp) covers them; a wrong formula misses by > 1e-2.
TEST(Stiffness, IsotropicMatchesMembranePaperEq16) {
  for (const auto& [E, nu] : {std::pair{210e9, 0.3}, std::pair{5e6, 0.3}, std::pair{278e6, 0.491},
                              std::pair{1.0, -0.5}}) {
    const double f = E / ((1 + nu) * (1 - 2 * nu));
    mat::Matrix6 d = mat::Matrix6::Zero();
    d << f * (1 - nu), f * nu, f * nu, 0, 0, 0, //
        f * nu, f * (1 - nu), f * nu, 0, 0, 0,  //
        f * nu, f * nu, f * (1 - nu), 0, 0, 0,  //
        0, 0, 0, f * (1 - 2 * nu) / 2, 0, 0,    //
        0, 0, 0, 0, f * (1 - 2 * nu) / 2, 0,    //
        0, 0, 0, 0, 0, f * (1 - 2 * nu) / 2;
    EXPECT_LE(relDiff(mat::Stiffness::isotropic(E, nu).matrix(), d), 2e-15)
        << "E " << E << " nu " << nu;
  }
}

// Textbook: E = mu (3 lambda + 2 mu) / (lambda + mu), nu = lambda / (2 (lambda + mu)),
// so fromLame(lambda, mu) and isotropic(E, nu) are the same tensor; and its
// engineering constants give E and nu back. A few roundings: 1e-14 relative.
TEST(Stiffness, FromLameIsConsistentWithYoungAndPoisson) {
  const double lambda = 121.15e9, mu = 80.77e9;
  const double E = mu * (3 * lambda + 2 * mu) / (lambda + mu);
  const double nu = lambda / (2 * (lambda + mu));
  const mat::Stiffness a = mat::Stiffness::fromLame(lambda, mu);
  EXPECT_LE(relDiff(a.matrix(), mat::Stiffness::isotropic(E, nu).matrix()), 1e-14);
  EXPECT_EQ(a(0, 0), lambda + 2 * mu);
  EXPECT_EQ(a(0, 1), lambda);
  EXPECT_EQ(a(3, 3), mu); // engineering shear: tau = mu * gamma
  const mat::EngineeringConstants e = a.engineering();
  EXPECT_NEAR(e.E1, E, 1e-14 * E);
  EXPECT_NEAR(e.nu12, nu, 1e-14);
}

// Engineering constants of an isotropic tensor: E_i = E, nu_ij = nu,
// G_ij = E / (2 (1 + nu)). The compliance is a 6x6 inverse of a matrix with
// condition number (1+nu)/(1-2nu) < 10: 1e-14 relative covers its rounding.
TEST(Stiffness, EngineeringConstantsOfIsotropicGiveBackEAndNu) {
  const double E = 72.4e9, nu = 0.22, G = E / (2 * (1 + nu));
  const mat::EngineeringConstants e = mat::Stiffness::isotropic(E, nu).engineering();
  for (double x : {e.E1, e.E2, e.E3})
    EXPECT_NEAR(x, E, 1e-14 * E);
  for (double x : {e.G12, e.G23, e.G13})
    EXPECT_NEAR(x, G, 1e-14 * G);
  for (double x : {e.nu12, e.nu13, e.nu23, e.nu21, e.nu31, e.nu32})
    EXPECT_NEAR(x, nu, 1e-14);
}

// Orthotropic engineering constants: for Table 1 the compliance S = C^-1 is
// block diagonal, so G12 = c44, G23 = c55, G13 = c66 exactly as inverses of
// inverses (2 roundings), and reciprocity nu_ij / E_i = nu_ji / E_j holds.
TEST(Stiffness, EngineeringConstantsOfTable1) {
  const mat::EngineeringConstants e = mat::Stiffness(table1()).engineering();
  EXPECT_NEAR(e.G12, 80 * GPa, 1e-15 * 80 * GPa);
  EXPECT_NEAR(e.G23, 20 * GPa, 1e-15 * 20 * GPa);
  EXPECT_NEAR(e.G13, 30 * GPa, 1e-15 * 30 * GPa);
  EXPECT_NEAR(e.nu12 / e.E1, e.nu21 / e.E2, 1e-14 * std::abs(e.nu12 / e.E1));
  EXPECT_NEAR(e.nu23 / e.E2, e.nu32 / e.E3, 1e-14 * std::abs(e.nu23 / e.E2));
  // E1 = 1 / S11 with S11 = (c22 c33 - c23^2) / det of the 3x3 normal block
  // (Cramer's rule, by hand).
  const double c11 = 150, c12 = 40, c13 = 10, c22 = 150, c23 = 80, c33 = 150;
  const double det =
      c11 * (c22 * c33 - c23 * c23) - c12 * (c12 * c33 - c23 * c13) + c13 * (c12 * c23 - c22 * c13);
  const double E1 = det / (c22 * c33 - c23 * c23) * GPa;
  EXPECT_NEAR(e.E1, E1, 1e-14 * E1);
}

// ----------------------------------------------------------------- rotation

// The lamina rotation agrees with the definition of a fourth-order tensor
// rotation (81-term sums of O(1) products: 1e-13 relative is far above their
// rounding, far below any index or sign error).
TEST(Rotation, MatchesFourthOrderTensorDefinition) {
  std::mt19937_64 rng(7);
  const mat::Matrix6 c = randomSpd(rng);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::Matrix3d r = randomRotation(rng);
    EXPECT_LE(
        relDiff(mat::Stiffness(c).rotated(r).matrix(), lamina::test::rotateByDefinition(c, r)),
        1e-13);
  }
}

// Isotropy: Q C Q^T = C for every rotation. Tolerance as above.
TEST(Rotation, IsotropicTensorIsInvariantUnderRandomRotations) {
  std::mt19937_64 rng(11);
  const mat::Stiffness c = mat::Stiffness::isotropic(210e9, 0.3);
  for (int trial = 0; trial < 10; ++trial)
    EXPECT_LE(relDiff(c.rotated(randomRotation(rng)).matrix(), c.matrix()), 1e-13);
}

// A transversely isotropic material (aramid, axis x) is invariant under any
// rotation about x; about z by 30 degrees the axial and transverse moduli
// (124 vs 6.9 GPa) mix, an O(1) relative change.
TEST(Rotation, TransverselyIsotropicInvariantAboutItsAxisOnly) {
  const mat::Stiffness c = catalog().get("aramid").C;
  for (double deg : {7.0, 30.0, 45.0, 90.0, 133.7, 251.0})
    EXPECT_LE(relDiff(c.rotatedAboutX(deg * kPi / 180).matrix(), c.matrix()), 1e-13) << deg;
  EXPECT_GT(relDiff(c.rotatedAboutZ(30 * kPi / 180).matrix(), c.matrix()), 0.1);
  EXPECT_GT(relDiff(c.rotatedAboutY(30 * kPi / 180).matrix(), c.matrix()), 0.1);
}

// Rotations compose: twice 45 degrees = once 90 degrees (the 90-degree matrix
// exact). Two rotations of 36-term sums: 1e-13 relative.
TEST(Rotation, TwiceFortyFiveEqualsNinety) {
  std::mt19937_64 rng(3);
  const mat::Stiffness c(randomSpd(rng));
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Matrix3d r45 = mat::axisRotationDegrees(axis, 45);
    const Eigen::Matrix3d r90 = mat::axisRotationDegrees(axis, 90);
    EXPECT_LE(relDiff(c.rotated(r45).rotated(r45).matrix(), c.rotated(r90).matrix()), 1e-13);
  }
}

// Multiples of 90 degrees stay exact beyond an int's range of quarter turns:
// 90 (2^33 + 1) degrees is 2^33 + 1 quarter turns, i.e. one quarter turn
// (2^33 is a multiple of 4), and 90 (2^33 + 2) is a half turn. Both angles
// are exact doubles, so the rotation must equal the small angle's bit for
// bit (an int cast of 2^33 + 1 overflowed: identity in Release).
TEST(Rotation, HugeMultiplesOfNinetyDegreesReduceExactly) {
  const double turns33 = std::ldexp(1.0, 33);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(mat::axisRotationDegrees(axis, 90 * (turns33 + 1)),
              mat::axisRotationDegrees(axis, 90))
        << axis;
    EXPECT_EQ(mat::axisRotationDegrees(axis, 90 * (turns33 + 2)),
              mat::axisRotationDegrees(axis, 180))
        << axis;
    EXPECT_EQ(mat::axisRotationDegrees(axis, -90 * (turns33 + 1)),
              mat::axisRotationDegrees(axis, -90))
        << axis;
  }
}

// A quarter turn about z maps x -> y, y -> -x: an orthotropic tensor has C11
// and C22, C13 and C23, C55 (yz) and C66 (xz) swapped, C12, C33, C44
// unchanged, and no coupling created. The rotation matrix is exact (0, +-1)
// so the result is an exact permutation.
TEST(Rotation, QuarterTurnAboutZSwapsOrthotropicEntriesExactly) {
  const mat::Matrix6 c = table1();
  const mat::Matrix6 r = mat::Stiffness(c).rotated(mat::axisRotationDegrees(2, 90)).matrix();
  mat::Matrix6 expected = c;
  expected(0, 0) = c(1, 1);
  expected(1, 1) = c(0, 0);
  expected(0, 2) = expected(2, 0) = c(1, 2);
  expected(1, 2) = expected(2, 1) = c(0, 2);
  expected(4, 4) = c(5, 5);
  expected(5, 5) = c(4, 4);
  EXPECT_EQ(r, expected);
  // The Eigen rotation of 90 degrees (cos = 6e-17) agrees to rounding.
  EXPECT_LE(relDiff(mat::Stiffness(c).rotatedAboutZ(kPi / 2).matrix(), expected), 1e-15);
}

// ---------------------------------------------------------------- validation

TEST(Validate, AcceptsPhysicalTensors) {
  EXPECT_NO_THROW(mat::Stiffness::isotropic(210e9, 0.3).validate("steel"));
  EXPECT_NO_THROW(mat::Stiffness(table1()).validate("table1"));
}

TEST(Validate, RejectsNonSymmetricNamingTheMaterial) {
  std::mt19937_64 rng(5);
  mat::Matrix6 c = randomSpd(rng);
  c(0, 4) += 1e-3 * c(0, 0);
  const std::string msg = errorOf([&] { mat::Stiffness(c).validate("skewed-resin"); });
  EXPECT_NE(msg.find("skewed-resin"), std::string::npos) << msg;
  EXPECT_NE(msg.find("symmetric"), std::string::npos) << msg;
}

// nu = 0.6 exceeds the isotropic bound 0.5: eq. (16) built by hand has the
// eigenvalue E/(1+nu) * ... of the 1-2nu mode negative: indefinite.
TEST(Validate, RejectsIndefiniteNamingTheMaterial) {
  const double E = 1e9, nu = 0.6, f = E / ((1 + nu) * (1 - 2 * nu));
  mat::Matrix6 d = mat::Matrix6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      d(i, j) = f * nu;
    d(i, i) = f * (1 - nu);
    d(3 + i, 3 + i) = f * (1 - 2 * nu) / 2;
  }
  const std::string msg = errorOf([&] { mat::Stiffness(d).validate("auxetic-typo"); });
  EXPECT_NE(msg.find("auxetic-typo"), std::string::npos) << msg;
  EXPECT_NE(msg.find("positive definite"), std::string::npos) << msg;
  EXPECT_LT(mat::Stiffness(d).smallestEigenvalue(), 0);
  EXPECT_THROW(mat::Stiffness::isotropic(E, nu), lamina::Error);
}

TEST(Validate, RejectsNaNNamingTheMaterial) {
  mat::Matrix6 c = table1();
  c(2, 3) = c(3, 2) = std::nan("");
  const std::string msg = errorOf([&] { mat::Stiffness(c).validate("nan-ply"); });
  EXPECT_NE(msg.find("nan-ply"), std::string::npos) << msg;
  EXPECT_NE(msg.find("NaN"), std::string::npos) << msg;
  c(2, 3) = c(3, 2) = INFINITY;
  EXPECT_NE(errorOf([&] { mat::Stiffness(c).validate("inf-ply"); }).find("inf-ply"),
            std::string::npos);
}

// ------------------------------------------------------------------ symmetry

TEST(Symmetry, ClassifiesIsotropic) {
  EXPECT_EQ(mat::classify(mat::Stiffness::isotropic(210e9, 0.3)).cls,
            mat::SymmetryClass::Isotropic);
}

// Cubic: C11 = C22 = C33, C12 = C13 = C23, C44 = C55 = C66 with C44 !=
// (C11 - C12)/2 (Zener ratio 2 C44 / (C11 - C12) = 1.6 here).
TEST(Symmetry, ClassifiesCubic) {
  mat::Matrix6 c = mat::Matrix6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      c(i, j) = 100 * GPa;
    c(i, i) = 200 * GPa;
    c(3 + i, 3 + i) = 80 * GPa;
  }
  EXPECT_EQ(mat::classify(mat::Stiffness(c)).cls, mat::SymmetryClass::Cubic);
}

TEST(Symmetry, ClassifiesTransverselyIsotropicWithAxis) {
  const mat::Symmetry s = mat::classify(catalog().get("aramid").C);
  EXPECT_EQ(s.cls, mat::SymmetryClass::TransverselyIsotropic);
  EXPECT_EQ(s.axis, 0);
  // The same material turned so that its axis is z.
  const mat::Symmetry sz =
      mat::classify(catalog().get("aramid").C.rotated(mat::axisRotationDegrees(1, 90)));
  EXPECT_EQ(sz.cls, mat::SymmetryClass::TransverselyIsotropic);
  EXPECT_EQ(sz.axis, 2);
}

TEST(Symmetry, ClassifiesTable1AsOrthotropic) {
  EXPECT_EQ(mat::classify(mat::Stiffness(table1())).cls, mat::SymmetryClass::Orthotropic);
}

// Table 1 turned 30 degrees about z keeps only the two-fold axis z.
TEST(Symmetry, ClassifiesRotatedTable1AsMonoclinicAboutZ) {
  const mat::Symmetry s = mat::classify(mat::Stiffness(table1()).rotatedAboutZ(30 * kPi / 180));
  EXPECT_EQ(s.cls, mat::SymmetryClass::Monoclinic);
  EXPECT_EQ(s.axis, 2);
}

TEST(Symmetry, ClassifiesRandomSpdAsTriclinic) {
  std::mt19937_64 rng(13);
  EXPECT_EQ(mat::classify(mat::Stiffness(randomSpd(rng))).cls, mat::SymmetryClass::Triclinic);
  EXPECT_EQ(mat::toString(mat::SymmetryClass::Triclinic), "triclinic");
}

// ------------------------------------------------------- bounds and index

// Isotropic: K_V = K_R = E / (3 (1 - 2 nu)), G_V = G_R = E / (2 (1 + nu)),
// A^U = 0 (to rounding: 1e-14).
TEST(Bounds, IsotropicVoigtAndReussEqualTextbookModuli) {
  const double E = 210e9, nu = 0.3;
  const mat::Stiffness c = mat::Stiffness::isotropic(E, nu);
  const double K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  EXPECT_NEAR(mat::voigtBulk(c), K, 1e-14 * K);
  EXPECT_NEAR(mat::reussBulk(c), K, 1e-14 * K);
  EXPECT_NEAR(mat::voigtShear(c), G, 1e-14 * G);
  EXPECT_NEAR(mat::reussShear(c), G, 1e-14 * G);
  EXPECT_NEAR(mat::anisotropyIndex(c), 0.0, 1e-13);
}

// Cubic: K_V = K_R, and A^U = (6/5) (sqrt(A) - 1/sqrt(A))^2 with Zener ratio
// A = 2 C44 / (C11 - C12) (Ranganathan and Ostoja-Starzewski 2008).
TEST(Bounds, CubicAnisotropyIndexMatchesZenerFormula) {
  const double c11 = 168.4 * GPa, c12 = 121.4 * GPa, c44 = 75.4 * GPa; // copper
  mat::Matrix6 c = mat::Matrix6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      c(i, j) = c12;
    c(i, i) = c11;
    c(3 + i, 3 + i) = c44;
  }
  const double A = 2 * c44 / (c11 - c12);
  const double expected = 1.2 * std::pow(std::sqrt(A) - 1 / std::sqrt(A), 2);
  EXPECT_NEAR(mat::anisotropyIndex(mat::Stiffness(c)), expected, 1e-12 * expected);
}

// Hill: Voigt bounds Reuss from above for every stiffness; A^U > 0 unless isotropic.
TEST(Bounds, VoigtAboveReussAndIndexPositive) {
  std::mt19937_64 rng(17);
  std::vector<mat::Stiffness> cases{mat::Stiffness(table1()), catalog().get("aramid").C,
                                    mat::Stiffness(randomSpd(rng)), mat::Stiffness(randomSpd(rng))};
  for (const mat::Stiffness& c : cases) {
    EXPECT_GE(mat::voigtBulk(c), mat::reussBulk(c));
    EXPECT_GE(mat::voigtShear(c), mat::reussShear(c));
    EXPECT_GT(mat::anisotropyIndex(c), 1e-6);
  }
}

// ------------------------------------------------------------------ catalog

// Table 1 of the membrane paper, read back from the catalog bit-exactly.
TEST(Catalog, Table1ReadsBackExactly) {
  const mat::CatalogEntry& e = catalog().get("table1-anisotropic");
  EXPECT_EQ(e.C.matrix(), table1());
  EXPECT_GT(e.density, 0);
}

// Every catalog entry has a valid stiffness and a positive density.
TEST(Catalog, EveryEntryIsValid) {
  for (const std::string& name : catalog().names()) {
    const mat::CatalogEntry& e = catalog().get(name);
    EXPECT_NO_THROW(e.C.validate(name));
    EXPECT_GT(e.density, 0) << name;
    EXPECT_FALSE(e.source.empty()) << name;
  }
}

// Isotropic entries carry the seed's numbers: vinyl fabric E = 5 MPa
// (drag paper section 4.2), nu = 0.3 chosen.
TEST(Catalog, VinylFabricHasDragPaperModulus) {
  const mat::EngineeringConstants e = catalog().get("vinyl-fabric").C.engineering();
  EXPECT_NEAR(e.E1, 5e6, 1e-14 * 5e6);
}
