// Conversions between lamina order and the other 6x6 orders (Voigt, Mandel,
// Abaqus, the Abaqus/CalculiX and LS-DYNA card lists): round trips on a
// random triclinic matrix and individual entries against the orders that
// DESIGN.md and the codes' manuals document.

#include "materials/conversions.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mat = lamina::materials;
using lamina::test::randomRotation;
using lamina::test::randomSpd;
using lamina::test::relDiff;

namespace {

// Lamina indices: 0 xx, 1 yy, 2 zz, 3 xy, 4 yz, 5 xz.
enum { XX = 0, YY = 1, ZZ = 2, XY = 3, YZ = 4, XZ = 5 };

class ConversionsTest : public ::testing::Test {
protected:
  std::mt19937_64 rng{20261122};
  mat::Matrix6 c = randomSpd(rng);
};

} // namespace

// Pure permutations copy doubles: the round trips must be bit-exact.
TEST_F(ConversionsTest, VoigtRoundTripIsExact) {
  EXPECT_EQ(mat::fromVoigt(mat::toVoigt(c)), c);
  EXPECT_EQ(mat::toVoigt(mat::fromVoigt(c)), c);
}

TEST_F(ConversionsTest, AbaqusRoundTripIsExact) {
  EXPECT_EQ(mat::fromAbaqus(mat::toAbaqus(c)), c);
  EXPECT_EQ(mat::toAbaqus(mat::fromAbaqus(c)), c);
}

TEST_F(ConversionsTest, AbaqusCardValuesRoundTripIsExact) {
  EXPECT_EQ(mat::fromAbaqusCardValues(mat::abaqusCardValues(c)), c);
}

TEST_F(ConversionsTest, LsdynaCardValuesRoundTripIsExact) {
  EXPECT_EQ(mat::fromLsdynaCardValues(mat::lsdynaCardValues(c)), c);
}

// Mandel multiplies shear rows/columns by sqrt(2) and divides back: each entry
// goes through at most four roundings of 2^-53 relative, so 1e-15 relative
// (about 4.5 ulp) bounds the round trip.
TEST_F(ConversionsTest, MandelRoundTripWithin1e15) {
  EXPECT_LE(relDiff(mat::fromMandel(mat::toMandel(c)), c), 1e-15);
  EXPECT_LE(relDiff(mat::toMandel(mat::fromMandel(c)), c), 1e-15);
}

// Standard Voigt order 11 22 33 23 13 12: Voigt (3,3) is yz-yz, (4,4) xz-xz,
// (5,5) xy-xy, (0,3) is C1123 = lamina (xx, yz).
TEST_F(ConversionsTest, VoigtEntriesFollowStandardOrder) {
  const mat::Matrix6 v = mat::toVoigt(c);
  EXPECT_EQ(v(3, 3), c(YZ, YZ));
  EXPECT_EQ(v(4, 4), c(XZ, XZ));
  EXPECT_EQ(v(5, 5), c(XY, XY));
  EXPECT_EQ(v(0, 3), c(XX, YZ));
  EXPECT_EQ(v(1, 5), c(YY, XY));
  EXPECT_EQ(v(3, 4), c(YZ, XZ));
  EXPECT_EQ(v(2, 2), c(ZZ, ZZ));
}

// Mandel: normal-shear entries carry sqrt(2), shear-shear entries carry 2.
// One multiplication each: 1 ulp, checked to 2.3e-16 relative.
TEST_F(ConversionsTest, MandelEntriesCarrySqrt2Scaling) {
  const mat::Matrix6 m = mat::toMandel(c);
  const double tol = 2.3e-16;
  EXPECT_EQ(m(0, 0), c(XX, XX));
  EXPECT_EQ(m(1, 2), c(YY, ZZ));
  EXPECT_NEAR(m(0, 3), std::sqrt(2.0) * c(XX, YZ), tol * std::abs(m(0, 3)));
  EXPECT_NEAR(m(2, 5), std::sqrt(2.0) * c(ZZ, XY), tol * std::abs(m(2, 5)));
  EXPECT_NEAR(m(3, 3), 2.0 * c(YZ, YZ), 2 * tol * std::abs(m(3, 3)));
  EXPECT_NEAR(m(4, 5), 2.0 * c(XZ, XY), 2 * tol * std::abs(m(4, 5)));
}

// Abaqus order 11 22 33 12 13 23.
TEST_F(ConversionsTest, AbaqusEntriesFollowAbaqusOrder) {
  const mat::Matrix6 a = mat::toAbaqus(c);
  EXPECT_EQ(a(3, 3), c(XY, XY)); // D1212
  EXPECT_EQ(a(4, 4), c(XZ, XZ)); // D1313
  EXPECT_EQ(a(5, 5), c(YZ, YZ)); // D2323
  EXPECT_EQ(a(0, 5), c(XX, YZ)); // D1123
  EXPECT_EQ(a(3, 4), c(XY, XZ)); // D1213
}

// Abaqus *ELASTIC, TYPE=ANISOTROPIC card order (Abaqus keywords manual):
// D1111 D1122 D2222 D1133 D2233 D3333 D1112 D2212 D3312 D1212 D1113 D2213
// D3313 D1213 D1313 D1123 D2223 D3323 D1223 D1323 D2323 (1-based #1..#21).
TEST_F(ConversionsTest, AbaqusCardValuesFollowManualOrder) {
  const auto v = mat::abaqusCardValues(c);
  EXPECT_EQ(v[0], c(XX, XX));  // #1 D1111
  EXPECT_EQ(v[1], c(XX, YY));  // #2 D1122
  EXPECT_EQ(v[2], c(YY, YY));  // #3 D2222
  EXPECT_EQ(v[3], c(XX, ZZ));  // #4 D1133
  EXPECT_EQ(v[5], c(ZZ, ZZ));  // #6 D3333
  EXPECT_EQ(v[6], c(XX, XY));  // #7 D1112 = lamina C(0,3)
  EXPECT_EQ(v[9], c(XY, XY));  // #10 D1212
  EXPECT_EQ(v[10], c(XX, XZ)); // #11 D1113
  EXPECT_EQ(v[13], c(XY, XZ)); // #14 D1213
  EXPECT_EQ(v[14], c(XZ, XZ)); // #15 D1313
  EXPECT_EQ(v[15], c(XX, YZ)); // #16 D1123
  EXPECT_EQ(v[18], c(XY, YZ)); // #19 D1223
  EXPECT_EQ(v[19], c(XZ, YZ)); // #20 D1323
  EXPECT_EQ(v[20], c(YZ, YZ)); // #21 D2323
}

// LS-DYNA *MAT_ANISOTROPIC_ELASTIC: C11 C12 C22 C13 C23 C33 C14 C24 C34 C44
// C15 C25 C35 C45 C55 C16 C26 C36 C46 C56 C66 in order xx yy zz xy yz zx.
TEST_F(ConversionsTest, LsdynaCardValuesFollowManualOrder) {
  const auto v = mat::lsdynaCardValues(c);
  EXPECT_EQ(v[0], c(XX, XX));  // C11
  EXPECT_EQ(v[1], c(XX, YY));  // C12
  EXPECT_EQ(v[4], c(YY, ZZ));  // C23
  EXPECT_EQ(v[6], c(XX, XY));  // #7 C14 = lamina C(0,3)
  EXPECT_EQ(v[9], c(XY, XY));  // #10 C44
  EXPECT_EQ(v[10], c(XX, YZ)); // #11 C15
  EXPECT_EQ(v[14], c(YZ, YZ)); // #15 C55
  EXPECT_EQ(v[15], c(XX, XZ)); // #16 C16
  EXPECT_EQ(v[19], c(YZ, XZ)); // #20 C56
  EXPECT_EQ(v[20], c(XZ, XZ)); // #21 C66
}

// Upper triangle row by row (the `materials add --constants` order).
TEST_F(ConversionsTest, UpperTriangleRowByRowRoundTripIsExact) {
  const mat::Stiffness s(c);
  const auto v = s.upperTriangle();
  EXPECT_EQ(v[1], c(0, 1));
  EXPECT_EQ(v[5], c(0, 5));
  EXPECT_EQ(v[6], c(1, 1));
  EXPECT_EQ(v[20], c(5, 5));
  EXPECT_EQ(mat::Stiffness::fromUpperTriangle(v).matrix(), c);
}

// The Mandel rotation is orthogonal (orthonormal basis of symmetric tensors):
// Q Q^T = I. Entries are sums of up to nine products of O(1) numbers, so 1e-14
// absolute bounds the rounding; an error in the basis gives O(1) defects.
TEST_F(ConversionsTest, MandelRotationIsOrthogonal) {
  for (int trial = 0; trial < 5; ++trial) {
    const mat::Matrix6 q = mat::mandelRotation(randomRotation(rng));
    EXPECT_LE((q * q.transpose() - mat::Matrix6::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  }
}

// (R eps R^T)_M = Q eps_M, checked on a random strain through the strain
// helpers (engineering shear in lamina order, tensorial in Mandel form).
TEST_F(ConversionsTest, MandelRotationRotatesStrainTensors) {
  const Eigen::Matrix3d r = randomRotation(rng);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix3d eps;
  eps << u(rng), u(rng), u(rng), 0, u(rng), u(rng), 0, 0, u(rng);
  eps = (eps + eps.transpose()).eval();
  const auto toMandelVector = [](const Eigen::Matrix3d& e) {
    Eigen::Matrix<double, 6, 1> m;
    const double s = std::sqrt(2.0);
    m << e(0, 0), e(1, 1), e(2, 2), s * e(1, 2), s * e(0, 2), s * e(0, 1);
    return m;
  };
  const Eigen::Matrix<double, 6, 1> lhs = toMandelVector(r * eps * r.transpose());
  const Eigen::Matrix<double, 6, 1> rhs = mat::mandelRotation(r) * toMandelVector(eps);
  EXPECT_LE((lhs - rhs).cwiseAbs().maxCoeff(), 1e-14);
  // The strain helpers are inverse to each other and use gamma = 2 eps.
  const auto v = mat::strainToLamina(eps);
  EXPECT_EQ(v(3), 2 * eps(0, 1));
  EXPECT_EQ(v(4), 2 * eps(1, 2));
  EXPECT_EQ(v(5), 2 * eps(0, 2));
  EXPECT_EQ(mat::strainFromLamina(v), eps);
}
