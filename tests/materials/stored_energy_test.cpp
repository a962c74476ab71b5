// ConstitutiveLaw::storedEnergy, the energy a stress returns on elastic
// unloading: for a linear law eps . C eps / 2 (the Voigt factor of the shear
// by hand: G gamma^2 / 2); for GVBO sigma . C(J)^-1 sigma / 2, written by hand
// for an isotropic C as p^2 / (2 K) + s : s / (4 G); for a reduced-order
// cell the sum over partitions, on the exact laminate equal to eps^c . C_eff
// eps^c / 2 (Hill's lemma).

#include "laminate_reduced_order.hpp"
#include "materials/catalog.hpp"
#include "materials/gvbo_law.hpp"
#include "materials/reduced_order_law.hpp"
#include "reduced_order_cells.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace mat = lamina::materials;
using mat::Vector6;

namespace {

/// sigma . C^-1 sigma / 2 of an isotropic C (K, G) by hand: the mean stress
/// p with the bulk compliance, the deviator s (tensor components, shear
/// counted twice in s : s) with the shear compliance.
double isotropicEnergy(const Vector6& sigma, double K, double G) {
  const double p = sigma.head<3>().sum() / 3;
  Vector6 s = sigma;
  s.head<3>().array() -= p;
  const double ss = s.head<3>().squaredNorm() + 2 * s.tail<3>().squaredNorm();
  return p * p / (2 * K) + ss / (4 * G);
}

double bulk(const mat::GvboModuli& m) {
  return m.lambda + 2 * m.G / 3;
}

} // namespace

// Any SPD C: storedEnergy(C eps) = eps . C eps / 2 to the round-off of an
// LDL^T solve (cond(C) ~ 1e2 for these matrices: 1e-13 relative); a pure
// engineering shear gamma: G gamma^2 / 2 (the Voigt factor: sigma_xy = G
// gamma, eps_xy = gamma / 2, so sigma : eps = G gamma^2).
TEST(StoredEnergy, LinearLawIsTheQuadraticForm) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e-3, 1e-3);
  for (int trial = 0; trial < 5; ++trial) {
    const mat::Matrix6 C = lamina::test::randomSpd(rng);
    const mat::LinearElasticLaw law(mat::LawKind::Anisotropic, mat::Stiffness(C));
    Vector6 eps;
    for (int i = 0; i < 6; ++i)
      eps[i] = u(rng);
    const double exact = 0.5 * eps.dot(C * eps);
    EXPECT_NEAR(law.storedEnergy(C * eps, nullptr, 1.0), exact, 1e-13 * exact);
  }
  const double E = 2e9, nu = 0.3, G = E / (2 * (1 + nu)), gamma = 1e-3;
  const mat::LinearElasticLaw iso(mat::LawKind::Isotropic, mat::Stiffness::isotropic(E, nu));
  Vector6 tau = Vector6::Zero();
  tau[4] = G * gamma; // yz
  EXPECT_NEAR(iso.storedEnergy(tau, nullptr, 1.0), G * gamma * gamma / 2,
              1e-14 * G * gamma * gamma);
}

// GVBO along a compressive and sheared history (J < 1: the moduli of eqs.
// 13-16 differ from the initial ones): storedEnergy > 0 and equals the hand
// formula with K(J), G(J) to round-off (1e-12 relative).
TEST(StoredEnergy, GvboIsTheComplementaryEnergyAtJ) {
  static const mat::Catalog cat;
  const mat::GvboLaw law(*cat.get("polyurea-gvbo").gvbo);
  std::vector<double> state(mat::GvboState::kSize);
  Vector6 E;
  E << -0.02, -0.01, -0.015, 0.05, 0.01, -0.03;
  const Vector6 eps = lamina::test::loadAlong(law, E, 50, 1e-5, state);
  const Vector6 sigma = Eigen::Map<const Vector6>(state.data() + mat::GvboState::kSigma);
  const double J = 1 + eps.head<3>().sum();
  const mat::GvboModuli m = mat::gvboModuli(law.parameters(), J);
  ASSERT_GT(m.G, 1.01 * mat::gvboModuli(law.parameters(), 1.0).G); // J matters here
  const double W = law.storedEnergy(sigma, state.data(), J);
  EXPECT_GT(W, 0.0);
  EXPECT_NEAR(W, isotropicEnergy(sigma, bulk(m), m.G), 1e-12 * W);
  EXPECT_EQ(law.storedEnergy(Vector6::Zero(), state.data(), J), 0.0);
}

// A linear reduced-order laminate (two elastic layers, exact A and P): the
// stored energy of its stress C_eff eps is eps . C_eff eps / 2 and the sum
// c_a eps_a . L_a eps_a / 2 over the layer strains of the independent oracle
// (Hill's lemma: equal for the exact laminate). Round-off: 1e-12.
TEST(StoredEnergy, LinearLaminateFollowsHillsLemma) {
  const mat::LawSpec soft = lamina::test::hardElastic();
  mat::LawSpec stiff;
  stiff.kind = mat::LawKind::Isotropic;
  stiff.C = mat::Stiffness::isotropic(70e9, 0.22);
  const std::vector<double> c{0.3, 0.7};
  const mat::ReducedOrderLaw law("lin", lamina::test::laminateCell({soft, stiff}, {0, 1}, c));
  ASSERT_TRUE(law.isLinear());
  Vector6 eps;
  eps << 1e-3, -4e-4, 2e-3, 7e-4, -1e-3, 5e-4;
  const mat::Matrix6 C = law.elasticStiffness().matrix();
  const double W = law.storedEnergy(C * eps, nullptr, 1.0);
  EXPECT_NEAR(W, 0.5 * eps.dot(C * eps), 1e-12 * W);
  const std::vector<mat::Matrix6> L{soft.C.matrix(), stiff.C.matrix()};
  const auto layers =
      lamina::test::laminateLayerStrains(L, c, eps, {Vector6::Zero(), Vector6::Zero()});
  double sum = 0;
  for (std::size_t a = 0; a < 2; ++a)
    sum += c[a] * 0.5 * layers[a].dot(L[a] * layers[a]);
  EXPECT_NEAR(W, sum, 1e-12 * W);
}

// The chapter's GVBO soft / elastic hard laminate after an inelastic history
// (small strain): storedEnergy = sum c_a W_a with the soft layer's W by hand
// (its stress from its state, K and G at its J = 1 + tr eps_a) and the hard
// layer's eps . L eps / 2, to round-off (1e-12). The law forms J_a from the
// coarse J and sum c_a tr eps_a, which equals tr eps^c only to its Newton
// tolerance (1e-10 of the strain, checked); the path dilates the soft layer
// (J_a > 1, checked), where eqs. 13-16 keep the moduli at their initial
// values, so that difference does not reach W.
TEST(StoredEnergy, GvboLaminateSumsItsPartitions) {
  const mat::ReducedOrderLaw law("pu", lamina::test::polyureaLaminate());
  std::vector<double> state;
  Vector6 E;
  E << 0.03, -0.01, 0.0, 0.04, 0.0, 0.02;
  const Vector6 eps = lamina::test::loadAlong(law, E, 40, 1e-4, state);
  const double J = 1 + eps.head<3>().sum();
  const mat::GvboLaw soft(*lamina::test::softGvbo().gvbo);
  const int o0 = law.stateOffset(0), o1 = law.stateOffset(1);
  const Vector6 eps0 = Eigen::Map<const Vector6>(state.data() + o0);
  const Vector6 eps1 = Eigen::Map<const Vector6>(state.data() + o1);
  const Vector6 sig0 = Eigen::Map<const Vector6>(state.data() + o0 + 6 + mat::GvboState::kSigma);
  ASSERT_GT(1 + eps0.head<3>().sum(), 1.0);
  const mat::GvboModuli m0 = mat::gvboModuli(soft.parameters(), 1 + eps0.head<3>().sum());
  const mat::Matrix6 L1 = lamina::test::hardElastic().C.matrix();
  const double expected =
      0.81 * isotropicEnergy(sig0, bulk(m0), m0.G) + 0.19 * 0.5 * eps1.dot(L1 * eps1);
  const double W = law.storedEnergy(Vector6::Zero(), state.data(), J); // coarse sigma unused
  EXPECT_GT(W, 0.0);
  EXPECT_NEAR(W, expected, 1e-12 * W);
  // the partition strains average to the coarse strain to the Newton tolerance
  EXPECT_LE((0.81 * eps0 + 0.19 * eps1 - eps).cwiseAbs().maxCoeff(),
            1e-10 * eps.cwiseAbs().maxCoeff());
}

// The split of the work along an isochoric sheared path (J = 1): the work
// of the stress, by the trapezoid rule over the steps, is at least the stored
// energy. At 1e10 /s the path lasts 1e-12 s; at the overstress it reaches,
// Gamma ~ 2G 0.01 ~ 2e6 Pa, k = k1 (1 + Gamma / k2)^-k4 ~ 0.03 s and the
// flow rate Gamma / (E k) ~ 0.3 /s leaves an inelastic strain of 3e-13, 3e-11
// of the 0.01 driven: the law is elastic with constant C, sigma linear in
// eps, the trapezoid rule exact, so stored = work to 1e-9 (that flow plus
// the round-off of 100 steps). At 1e-2 /s the overstress relaxes: a good
// part of the work (more than 10 %) is dissipated.
TEST(StoredEnergy, GvboStoresTheWorkAtHighRateAndDissipatesAtLowRate) {
  static const mat::Catalog cat;
  const mat::GvboLaw law(*cat.get("polyurea-gvbo").gvbo);
  Vector6 E;
  E << 0.01, -0.006, -0.004, 0.008, -0.003, 0.005; // isochoric: J = 1
  for (double rate : {1e10, 1e-2}) {
    std::vector<double> state(mat::GvboState::kSize);
    law.initState(state.data());
    const int steps = 100;
    const double dt = 0.01 / rate / steps;
    Vector6 eps = Vector6::Zero(), sigma_n = Vector6::Zero(), sigma;
    double work = 0;
    for (int i = 1; i <= steps; ++i) {
      const Vector6 next = E * i / steps;
      const mat::PointStep s{eps, next, 1 + eps.head<3>().sum(), 1 + next.head<3>().sum(), dt};
      law.update(s, state.data(), state.data(), sigma, nullptr);
      work += 0.5 * (sigma_n + sigma).dot(next - eps);
      eps = next;
      sigma_n = sigma;
    }
    const double W = law.storedEnergy(sigma, state.data(), 1 + eps.head<3>().sum());
    EXPECT_GT(W, 0.0) << rate;
    EXPECT_LE(W, work * (1 + 1e-9)) << rate;
    if (rate > 1)
      EXPECT_NEAR(W, work, 1e-9 * work) << W / work - 1;
    else
      EXPECT_LT(W, 0.9 * work) << W / work;
  }
}
