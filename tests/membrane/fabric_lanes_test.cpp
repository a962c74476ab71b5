// The elastic fabric element in lanes (fabric_lanes.hpp): every lane's nodal
// forces are the one-element force's bits (the same sums in the same order,
// nothing fused) and, to round-off, fabricForces() of fabric_element.hpp;
// with the relaxed law exactly the lanes whose trial stress is not taut are
// handed back; each lane's stable step is its length over its fastest wave;
// and a model's force and stable step are those of its one-element loop.
// This file is compiled without fused multiply-adds, like the library's
// one-element path (membrane/CMakeLists.txt).
#include "helpers.hpp"
#include "membrane/model/fabric_element.hpp"
#include "membrane/model/fabric_lanes.hpp"
#include "membrane/model/large_deflection.hpp"
#include "membrane/model/relaxed_wrinkling.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace lamina::membrane;

namespace {

constexpr int W = kFabricLanes;

/// Eight triangles (three nodes each, nodes 3 l .. 3 l + 2) with random
/// reference shapes in the plane and random current positions in space.
struct Lanes {
  FabricLaneGroup g{};
  std::vector<double> x;           // current positions, 3 per node
  std::array<FabricElement, W> el; // reference data (frame: the plane's axes)
  std::array<double, W> length{};  // element lengths (any positive values)
};

/// @param stretch the mean stretch of the current positions
/// @param noise the random displacement of each node, relative to the element size
Lanes makeLanes(unsigned seed, double stretch, double noise) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Lanes L;
  L.x.resize(3 * 3 * W);
  for (int l = 0; l < W; ++l) {
    // a reference triangle of size ~0.01 m, counter-clockwise
    const double s = 0.01 * (1 + 0.5 * U(gen));
    const std::array<Eigen::Vector2d, 3> X = {
        Eigen::Vector2d(0.3 * s * U(gen), 0.3 * s * U(gen)),
        Eigen::Vector2d(s * (1 + 0.2 * U(gen)), 0.2 * s * U(gen)),
        Eigen::Vector2d(s * 0.3 * U(gen), s * (1 + 0.2 * U(gen)))};
    const double A2 = (X[1] - X[0]).x() * (X[2] - X[0]).y() - (X[2] - X[0]).x() * (X[1] - X[0]).y();
    FabricElement& el = L.el[static_cast<size_t>(l)];
    el.area0 = 0.5 * A2;
    el.frame.setIdentity();
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector2d& P = X[static_cast<size_t>((a + 1) % 3)];
      const Eigen::Vector2d& Q = X[static_cast<size_t>((a + 2) % 3)];
      el.dN[static_cast<size_t>(a)] = Eigen::Vector2d(P.y() - Q.y(), Q.x() - P.x()) / A2;
      el.nodes[static_cast<size_t>(a)] = 3 * l + a;
      L.g.node[a][l] = 3 * (3 * l + a);
      L.g.dN[2 * a][l] = el.dN[static_cast<size_t>(a)].x();
      L.g.dN[2 * a + 1][l] = el.dN[static_cast<size_t>(a)].y();
      const Eigen::Vector3d x(stretch * X[static_cast<size_t>(a)].x() + noise * s * U(gen),
                              stretch * X[static_cast<size_t>(a)].y() + noise * s * U(gen),
                              noise * s * U(gen));
      for (int c = 0; c < 3; ++c)
        L.x[static_cast<size_t>(3 * (3 * l + a) + c)] = x[c];
    }
    L.g.hA[l] = 1e-3 * el.area0;
    L.length[static_cast<size_t>(l)] = s * (1 + 0.1 * l);
  }
  return L;
}

/// An orthotropic plane-stress stiffness rotated by 0.4 rad (all nine
/// entries non-zero) and a pre-stress per thickness.
LinearLaneLaw makeLaw(bool relaxed, const Eigen::Vector3d& s0) {
  const double E1 = 2.0e9, E2 = 0.8e9, nu12 = 0.25, G = 0.3e9, nu21 = nu12 * E2 / E1;
  Eigen::Matrix3d C0;
  C0 << E1 / (1 - nu12 * nu21), nu21 * E1 / (1 - nu12 * nu21), 0, nu21 * E1 / (1 - nu12 * nu21),
      E2 / (1 - nu12 * nu21), 0, 0, 0, G;
  const double c = std::cos(0.4), s = std::sin(0.4);
  Eigen::Matrix3d T; // strain rotation ([E11, E22, 2 E12])
  T << c * c, s * s, c * s, s * s, c * c, -c * s, -2 * c * s, 2 * c * s, c * c - s * s;
  const Eigen::Matrix3d C = T.transpose() * C0 * T;
  LinearLaneLaw law;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      law.C[i][j] = C(i, j);
    law.s0[i] = s0[i];
  }
  law.relaxed = relaxed;
  return law;
}

Eigen::Matrix3d stiffness(const LinearLaneLaw& law) {
  Eigen::Matrix3d C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C(i, j) = law.C[i][j];
  return C;
}

std::array<Eigen::Vector3d, 3> positions(const Lanes& L, int l) {
  std::array<Eigen::Vector3d, 3> x;
  for (int a = 0; a < 3; ++a)
    x[static_cast<size_t>(a)] = Eigen::Map<const Eigen::Vector3d>(L.x.data() + 3 * (3 * l + a));
  return x;
}

/// The one-element force in LargeDeflection's order (deformation, then
/// linearStress's S = C_ps E + S0, row 2 pairing its last two terms, then
/// the element loop's h A0 F S dN_a), taut stress only. This file is compiled for the
/// baseline (no fused multiply-add), as the library's one-element path.
std::array<double, 9> orderedForce(const LinearLaneLaw& law, const Lanes& L, int l) {
  double F0[3] = {0, 0, 0}, F1[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      const double x = L.x[static_cast<size_t>(L.g.node[a][l] + c)];
      F0[c] += x * L.g.dN[2 * a][l];
      F1[c] += x * L.g.dN[2 * a + 1][l];
    }
  const double C0 = F0[0] * F0[0] + F0[1] * F0[1] + F0[2] * F0[2];
  const double C1 = F1[0] * F1[0] + F1[1] * F1[1] + F1[2] * F1[2];
  const double C2 = F0[0] * F1[0] + F0[1] * F1[1] + F0[2] * F1[2];
  const double E[3] = {0.5 * (C0 - 1), 0.5 * (C1 - 1), C2};
  const auto& K = law.C;
  const double S[3] = {K[0][0] * E[0] + K[0][1] * E[1] + K[0][2] * E[2] + law.s0[0],
                       K[1][0] * E[0] + K[1][1] * E[1] + K[1][2] * E[2] + law.s0[1],
                       (K[2][0] * E[0] + (K[2][1] * E[1] + K[2][2] * E[2])) + law.s0[2]};
  std::array<double, 9> f{};
  for (int c = 0; c < 3; ++c) {
    const double P0 = L.g.hA[l] * (F0[c] * S[0] + F1[c] * S[2]);
    const double P1 = L.g.hA[l] * (F0[c] * S[2] + F1[c] * S[1]);
    for (int a = 0; a < 3; ++a)
      f[static_cast<size_t>(3 * a + c)] = P0 * L.g.dN[2 * a][l] + P1 * L.g.dN[2 * a + 1][l];
  }
  return f;
}

} // namespace

// Stretched 5 % with 20 % random displacements (taut, slack and sheared
// lanes) under a pre-stress, no wrinkling law: every lane is taken, its
// forces equal the ordered one-element force bit for bit (the bits a run
// depends on: outputs unchanged by the lanes), and fabricForces() to 1e-12 of
// the largest force (different association order, round-off only).
TEST(FabricLanes, EveryLaneIsTheOneElementForceBitForBit) {
  const LinearLaneLaw law = makeLaw(false, Eigen::Vector3d(2e5, -1e5, 5e4));
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Lanes L = makeLanes(seed, 1.05, 0.2);
    double f[9][W];
    ASSERT_EQ(linearFabricForces(law, L.g, L.x.data(), f), (1u << W) - 1);
    for (int l = 0; l < W; ++l) {
      const std::array<double, 9> one = orderedForce(law, L, l);
      const FabricStress st =
          fabricStress(L.el[static_cast<size_t>(l)], positions(L, l), stiffness(law),
                       Eigen::Vector3d(law.s0[0], law.s0[1], law.s0[2]), WrinklingLaw::None);
      const Eigen::Matrix3d ref = fabricForces(L.el[static_cast<size_t>(l)], st, 1e-3);
      const double scale = ref.cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      for (int j = 0; j < 9; ++j) {
        EXPECT_EQ(f[j][l], one[static_cast<size_t>(j)]) << "seed " << seed << " lane " << l;
        EXPECT_NEAR(f[j][l], ref(j % 3, j / 3), 1e-12 * scale) << "seed " << seed << " lane " << l;
      }
    }
  }
}

// The relaxed law: a lane is taken exactly when its trial stress C_ps E + S0
// is positive semidefinite (checked here on fabricStress()'s trial stress),
// and its force is then the taut force; 0.1 % compression with random
// displacements of 3 % of the element size leaves lanes of both kinds.
TEST(FabricLanes, RelaxedLawHandsBackTheLanesNotTaut) {
  const LinearLaneLaw law = makeLaw(true, Eigen::Vector3d(3e6, 3e6, 0));
  int taken_total = 0, handed_back = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Lanes L = makeLanes(seed, 0.999, 0.03);
    double f[9][W];
    const std::uint32_t taken = linearFabricForces(law, L.g, L.x.data(), f);
    for (int l = 0; l < W; ++l) {
      const FabricStress st =
          fabricStress(L.el[static_cast<size_t>(l)], positions(L, l), stiffness(law),
                       Eigen::Vector3d(law.s0[0], law.s0[1], law.s0[2]), WrinklingLaw::None);
      const bool taut = positiveSemidefinite2(st.S[0], st.S[1], st.S[2]);
      EXPECT_EQ((taken >> l & 1u) != 0, taut) << "seed " << seed << " lane " << l;
      if (taut) {
        ++taken_total;
        const std::array<double, 9> one = orderedForce(law, L, l);
        for (int j = 0; j < 9; ++j)
          EXPECT_EQ(f[j][l], one[static_cast<size_t>(j)]);
      } else {
        ++handed_back;
      }
    }
  }
  EXPECT_GT(taken_total, 20); // both branches exercised
  EXPECT_GT(handed_back, 20);
}

// Each lane's stable step against the wave speed computed here from the
// eigenvalues of C = F^T F and of S (Eigen's solver, an independent route):
// sqrt((M max(lambda_max(C), 1) + max(lambda_max(S), 0)) / rho), or the rest
// speed where that is larger; the rest speed is set between the lanes'
// speeds so that both branches are taken. Tolerance 1e-13: the two
// eigenvalue routes differ by round-off.
TEST(FabricLanes, StableStepIsTheLengthOverTheFastestWave) {
  const LinearLaneLaw law = makeLaw(false, Eigen::Vector3d(2e5, 1e5, 5e4));
  const double M = 2.2e9, rho = 1100;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Lanes L = makeLanes(seed, 1.02, 0.1);
    std::array<double, W> speed{};
    for (int l = 0; l < W; ++l) {
      const FabricStress st =
          fabricStress(L.el[static_cast<size_t>(l)], positions(L, l), stiffness(law),
                       Eigen::Vector3d(law.s0[0], law.s0[1], law.s0[2]), WrinklingLaw::None);
      const Eigen::Matrix2d C = st.F.transpose() * st.F;
      Eigen::Matrix2d S;
      S << st.S[0], st.S[2], st.S[2], st.S[1];
      const double lc = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(C).eigenvalues()[1];
      const double ls = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S).eigenvalues()[1];
      speed[static_cast<size_t>(l)] = std::sqrt((M * std::max(lc, 1.0) + std::max(ls, 0.0)) / rho);
    }
    std::array<double, W> sorted = speed;
    std::sort(sorted.begin(), sorted.end());
    const LaneWave wave{M, rho, 0.5 * (sorted[3] + sorted[4])};
    double dt[W];
    ASSERT_EQ(linearFabricStableSteps(law, wave, L.g, L.x.data(), L.length.data(), dt),
              (1u << W) - 1);
    for (int l = 0; l < W; ++l) {
      const double expected =
          L.length[static_cast<size_t>(l)] / std::max(speed[static_cast<size_t>(l)], wave.rest);
      EXPECT_NEAR(dt[l], expected, 1e-13 * expected) << "seed " << seed << " lane " << l;
    }
  }
}

// The model's internal force and stable step with the lanes and with the
// one-element loop (LargeDeflection::useLanes) on a 50 x 50 square whose
// plane-stress stiffness couples shear and stretch (an isotropic sheet's
// 6x6 given xx-xy and yy-xy terms, as an angle-ply laminate has), pre-stressed
// and tension-only with the relaxed law: at a random configuration (taut,
// wrinkled and slack elements) the two give the same bits, on one thread and
// on two.
TEST(FabricLanes, ModelForceAndStableStepEqualTheElementLoopBitForBit) {
  Model model = test::modelFromText(test::elasticSquare(
      50, "tension_only = true\nprestress = [0.2, 0.1, 0.03]\n[time]\nt_end = 1.0\n"));
  auto& D = model.sections[0].D; // lamina order: 0 xx, 1 yy, 2 zz, 3 xy
  const double c = 0.3 * std::sqrt(D(0, 0) * D(3, 3));
  D(0, 3) = D(3, 0) = c;
  D(1, 3) = D(3, 1) = -0.5 * c;
  const LargeDeflection ld(model);
  const Eigen::Matrix3d C = ld.planeStress(0);
  ASSERT_NE(C(2, 0), 0.0); // the coupling the summation order matters for
  ASSERT_NE(C(2, 1), 0.0);
  Eigen::VectorXd u = 0.002 * Eigen::VectorXd::Random(ld.numDofs());
  const int before = omp_get_max_threads();
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    Eigen::VectorXd f_lanes, f_one;
    LargeDeflection::useLanes(true);
    ld.internalForce(u, f_lanes);
    const double dt_lanes = ld.currentStableStep(u);
    LargeDeflection::useLanes(false);
    ld.internalForce(u, f_one);
    const double dt_one = ld.currentStableStep(u);
    LargeDeflection::useLanes(true);
    EXPECT_TRUE(f_lanes == f_one) << threads << " threads: largest difference "
                                  << (f_lanes - f_one).lpNorm<Eigen::Infinity>();
    EXPECT_EQ(dt_lanes, dt_one) << threads << " threads";
    EXPECT_GT(f_lanes.lpNorm<Eigen::Infinity>(), 0.0);
  }
  omp_set_num_threads(before);
}
