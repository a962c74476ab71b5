// The single-precision path of the linear solver (tol >= 1e-6: the cell
// operator and the CG vectors in float) against numbers from outside it:
// the closed-form Fourier symbol of the operator and the exact laminate
// formula within the a-priori bound of the energy estimate (the homogeneous
// cell at tol 1e-3: exact_test.cpp).

#include "oracles.hpp"

#include "homogenize/cell_operator.hpp"
#include "homogenize/distribution.hpp"

#include <cmath>

namespace lamina::test {
namespace {

// For a homogeneous isotropic medium the operator is diagonal in Fourier
// space: a nodal mode u = a cos(xi . idx) gives f = K0(q) a cos(xi . idx)
// with K0 = mu |q|^2 I + (lambda + mu) q q^T and the rotated-scheme wave
// vector q_1 = 2 sin(xi_1/2) cos(xi_2/2) cos(xi_3/2) / h_1 (cyclically;
// green_operator.hpp). And u^T A u = a^T K0 a N / 2.
TEST(SinglePrecision, OperatorOnAFourierModeIsTheReferenceSymbol) {
  homogenize::Grid g;
  g.n = {8, 6, 10};
  g.h = {0.5, 0.8, 0.3};
  const double lambda = 2.1e9, mu = 0.7e9;
  const std::vector<Stiffness> C{Stiffness::fromLame(lambda, mu)};
  const auto dist = homogenize::Distribution::serial(g);
  const homogenize::CellOperator A(g, std::vector<std::int32_t>(g.size(), 0), C, dist);
  const int m[3] = {1, 2, 3}; // mode numbers
  double xi[3], q[3];
  for (int d = 0; d < 3; ++d)
    xi[d] = 2 * M_PI * m[d] / g.n[static_cast<std::size_t>(d)];
  for (int d = 0; d < 3; ++d) {
    const int e = (d + 1) % 3, f = (d + 2) % 3;
    q[d] = 2 * std::sin(xi[d] / 2) * std::cos(xi[e] / 2) * std::cos(xi[f] / 2) /
           g.h[static_cast<std::size_t>(d)];
  }
  const double a[3] = {0.3, -1.0, 0.6}; // amplitude per component
  double K0a[3], qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  for (int c = 0; c < 3; ++c)
    K0a[c] = mu * qq * a[c] + (lambda + mu) * q[c] * (q[0] * a[0] + q[1] * a[1] + q[2] * a[2]);
  const std::size_t N = g.size();
  std::vector<float> u(3 * N), f(3 * N);
  std::vector<double> wave(N); // cos(xi . idx) per node
  for (int i = 0; i < g.n[0]; ++i)
    for (int j = 0; j < g.n[1]; ++j)
      for (int k = 0; k < g.n[2]; ++k) {
        const std::size_t at = (static_cast<std::size_t>(i) * g.n[1] + j) * g.n[2] + k;
        wave[at] = std::cos(xi[0] * i + xi[1] * j + xi[2] * k);
        for (int c = 0; c < 3; ++c)
          u[c * N + at] = static_cast<float>(a[c] * wave[at]);
      }
  double energy = 0;
  std::array<double, 6> average{};
  A.apply(u.data(), {0, 0, 0, 0, 0, 0}, f.data(), &average, &energy);
  // Force scale: each force is about 30 float operations on values bounded
  // by (lambda + 2 mu) |q|max^2 |a|max (the largest single term); float's
  // unit round-off is 6e-8, so 1e-5 of that scale bounds the rounding.
  const double qmax2 =
      4.0 * (1 / (g.h[0] * g.h[0]) + 1 / (g.h[1] * g.h[1]) + 1 / (g.h[2] * g.h[2]));
  const double scale = (lambda + 2 * mu) * qmax2 * 1.0;
  double worst = 0;
  for (int c = 0; c < 3; ++c)
    for (std::size_t at = 0; at < N; ++at)
      worst = std::max(worst, std::abs(f[c * N + at] - K0a[c] * wave[at]));
  EXPECT_LT(worst, 1e-5 * scale);
  // and the forces are not all small: the mode's largest force is a visible
  // part of the scale, so the check above is not vacuous
  EXPECT_GT(std::max({std::abs(K0a[0]), std::abs(K0a[1]), std::abs(K0a[2])}), 1e-2 * scale);
  // energy: summed in double over float products; relative rounding 1e-6
  const double exact = (a[0] * K0a[0] + a[1] * K0a[1] + a[2] * K0a[2]) * static_cast<double>(N) / 2;
  EXPECT_NEAR(energy, exact, 1e-6 * exact);
  // a periodic fluctuation has zero mean strain, hence zero mean stress
  for (double s : average)
    EXPECT_LT(std::abs(s), 1e-6 * (lambda + 2 * mu) * std::sqrt(qmax2));
}

// A laminate of isotropic layers normal to z at tol 1e-3 (float operator):
// the exact laminate formula within the energy estimate's a-priori bound
// |C_jk(tol) - C_jk| <= res_j res_k sqrt(C0_jj C0_kk) / kappa
// (energy_estimate_test.cpp; kappa = min over phases of K/K0, G/G0, exact
// for isotropic phases) plus float rounding (1e-6 of max|C|: the operator's
// values carry 6e-8 relative, the sums are double).
/// The three-layer laminate of the tests below: layers normal to z, 5, 4
/// and 3 voxels thick.
struct Laminate {
  std::vector<Stiffness> C{Stiffness::isotropic(156e6, 0.494), Stiffness::isotropic(890e6, 0.491),
                           Stiffness::isotropic(3e9, 0.3)};
  std::array<int, 3> n{6, 6, 12};
  std::vector<std::int32_t> map;
  Matrix6 exact; ///< the exact laminate formula
  Laminate() : map(static_cast<std::size_t>(n[0] * n[1] * n[2])) {
    for (std::size_t at = 0; at < map.size(); ++at) {
      const int k = static_cast<int>(at % 12);
      map[at] = k < 5 ? 0 : k < 9 ? 1 : 2;
    }
    exact =
        laminate({C[0].matrix(), C[1].matrix(), C[2].matrix()}, {5.0 / 12, 4.0 / 12, 3.0 / 12}, 2);
  }
};

TEST(SinglePrecision, LaminateWithinTheEnergyBoundOfTheExactFormula) {
  const Laminate lam;
  const auto& C = lam.C;
  const auto r = homogenizeMap(lam.n, lam.map, C, 1e-3);
  ASSERT_EQ(r.precision, homogenize::Precision::Single);
  ASSERT_TRUE(r.float_vectors); // tol 1e-3 >= kFloatVectorsTol
  const Matrix6& exact = lam.exact;
  const Stiffness C0 = Stiffness::fromLame(r.lambda0, r.mu0);
  const double K0 = r.lambda0 + 2 * r.mu0 / 3;
  double kappa = 1e300;
  for (const auto& c : C)
    kappa = std::min({kappa, materials::voigtBulk(c) / K0, materials::voigtShear(c) / r.mu0});
  const double rounding = 1e-6 * exact.cwiseAbs().maxCoeff();
  for (int j = 0; j < 6; ++j)
    for (int k = 0; k < 6; ++k) {
      const double bound = r.cases[static_cast<std::size_t>(j)].residual *
                               r.cases[static_cast<std::size_t>(k)].residual *
                               std::sqrt(C0(j, j) * C0(k, k)) / kappa +
                           rounding;
      EXPECT_LE(std::abs(r.C(j, k) - exact(j, k)), bound) << "C(" << j << "," << k << ")";
    }
  expectWithinVoigtReuss(r.C.matrix(), C, {5.0 / 12, 4.0 / 12, 3.0 / 12});
}

// Single-precision transforms asked for at a tolerance below
// kFloatVectorsTol keep the operator and the CG vectors double: CG then
// reaches the true tol 1e-10 and C equals the exact laminate formula to the
// energy estimate's bound (about 1e-20 of max|C| at this residual) plus
// double rounding of sums over 432 voxels (1e-12 of max|C| with margin).
// Float vectors leave about 1e-8 of max|C| (their unit round-off 6e-8 on
// the stresses), which this bound refuses.
TEST(SinglePrecision, TightToleranceKeepsDoubleVectorsAndReachesTheExactLaminate) {
  const Laminate lam;
  const auto r = homogenizeMap(lam.n, lam.map, lam.C, 1e-10, {}, homogenize::Precision::Single);
  ASSERT_EQ(r.precision, homogenize::Precision::Single);
  EXPECT_FALSE(r.float_vectors);
  EXPECT_LE(relDiff(r.C.matrix(), lam.exact), 1e-12);
}

} // namespace
} // namespace lamina::test
