// The reduced-order build of a cell of two elastic phases (a sphere and an
// oblique ellipsoid in a matrix, 10^3 voxels) against relations that hold
// for ANY cell, with one partition per phase and with three k-means
// partitions per phase:
// - exact: sum_b c_b A^(b) = I and sum_b c_b P^(b a) = 0 (the mean of a
//   periodic strain is zero; only round-off remains);
// - to the solver tolerance: sum_a P^(b a) = I - A^(b) (a unit eigenstrain
//   on every partition is minus a unit macro strain: sum_a S^(a) = -H),
//   the reciprocity c_b L_b P^(b a) = (c_a L_a P^(a b))^T (Maxwell-Betti:
//   both are the bilinear form S^(b)^T A S^(a) per voxel), C = sum_b c_b
//   L_b A^(b) against the Homogenizer's C of the same voxels;
// - eq. 40: R is a Gram matrix (symmetric positive semi-definite), and from
//   sum_a S^(a) = -H: sum_ab R^(ab)_kk = rho <H_k . H_k>, and with one
//   density (h = H) sum_a Q^(a) = -D_lin and sum_ab R^(ab) = D_lin.
//
// Tolerances. The solves run to tol 1e-11 (strain error in the reference
// energy norm relative to a unit strain over the cell). A partition mean of
// that error is at most the rms error over sqrt(c_b) (c_b >= 1 % here) times
// the contrast factor sqrt(70e9 / 3e9) ~ 5: 5e-10, so 1e-8 on quantities of
// order one has a margin of 20. The exact sums are of 1000 terms of order
// one: 1e-12. C: the energy estimate's error is quadratic in the
// tolerance, the stress estimate's linear (~1e-11 of max|C|): 1e-10.

#include "homogenize/homogenizer.hpp"
#include "homogenize/reduced_order_builder.hpp"
#include "reduced_order_cells.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

namespace lamina::test {
namespace {

using materials::Matrix6;

constexpr double kTol = 1e-11;

struct Built {
  homogenize::ReducedOrderResult r;
  std::vector<materials::Stiffness> L;
};

Built build(int per_phase, double rho_stiff) {
  const std::array<int, 3> n{10, 10, 10};
  const std::vector<materials::ReducedOrderPhase> phases{
      isotropicPhase("matrix", 3e9, 0.4, 1100), isotropicPhase("stiff", 70e9, 0.25, rho_stiff)};
  homogenize::ReducedOrderOptions opt;
  opt.tol = kTol;
  if (per_phase > 0) {
    opt.partitions.method = homogenize::PartitionMethod::KMeans;
    opt.partitions.per_phase = per_phase;
  }
  homogenize::ReducedOrderBuilder b(cubeGrid(n, 1e-3), inclusionsMap(n), phases, true, opt);
  Built out{b.run(), {}};
  for (const auto& p : phases)
    out.L.push_back(p.law.C);
  return out;
}

class ReducedOrderIdentities : public ::testing::TestWithParam<int> {};

TEST_P(ReducedOrderIdentities, HoldOnACellOfInclusions) {
  const Built built = build(GetParam(), 2700);
  const materials::ReducedOrderModel& m = built.r.model;
  const int n = m.partitions();
  ASSERT_EQ(n, GetParam() > 0 ? 2 * GetParam() : 2);
  const Matrix6 I = Matrix6::Identity();
  Matrix6 sumA = Matrix6::Zero(), C = Matrix6::Zero();
  for (int b = 0; b < n; ++b) {
    const std::size_t ub = static_cast<std::size_t>(b);
    sumA += m.fraction[ub] * m.A[ub];
    C += m.fraction[ub] * built.L[static_cast<std::size_t>(m.partition_phase[ub])].matrix() *
         m.A[ub];
  }
  EXPECT_LT((sumA - I).cwiseAbs().maxCoeff(), 1e-12);
  double max_cLP = 0;
  for (int a = 0; a < n; ++a) {
    Matrix6 col = Matrix6::Zero();
    for (int b = 0; b < n; ++b) {
      const std::size_t ub = static_cast<std::size_t>(b), ua = static_cast<std::size_t>(a);
      col += m.fraction[ub] * m.P[ub * n + ua];
      max_cLP = std::max(max_cLP, (m.fraction[ub] *
                                   built.L[static_cast<std::size_t>(m.partition_phase[ub])].matrix() *
                                   m.P[ub * n + ua])
                                      .cwiseAbs()
                                      .maxCoeff());
    }
    EXPECT_LT(col.cwiseAbs().maxCoeff(), 1e-12) << "sum_b c_b P^(b " << a << ")";
  }
  for (int b = 0; b < n; ++b) {
    const std::size_t ub = static_cast<std::size_t>(b);
    Matrix6 row = Matrix6::Zero();
    for (int a = 0; a < n; ++a)
      row += m.P[ub * n + static_cast<std::size_t>(a)];
    EXPECT_LT((row - (I - m.A[ub])).cwiseAbs().maxCoeff(), 1e-8) << "sum_a P^(" << b << " a)";
    for (int a = 0; a < n; ++a) { // reciprocity, relative to the largest c L P
      const std::size_t ua = static_cast<std::size_t>(a);
      const Matrix6 ba = m.fraction[ub] *
                         built.L[static_cast<std::size_t>(m.partition_phase[ub])].matrix() *
                         m.P[ub * n + ua];
      const Matrix6 ab = m.fraction[ua] *
                         built.L[static_cast<std::size_t>(m.partition_phase[ua])].matrix() *
                         m.P[ua * n + ub];
      EXPECT_LT((ba - ab.transpose()).cwiseAbs().maxCoeff(), 1e-8 * max_cLP) << b << ", " << a;
    }
  }
  // C against the linear homogenizer on the same voxels (energy estimate)
  homogenize::Options o;
  o.tol = kTol;
  o.estimate = homogenize::Estimate::Energy;
  o.precision = homogenize::Precision::Double;
  const std::array<int, 3> grid_n{10, 10, 10};
  homogenize::Homogenizer h(cubeGrid(grid_n, 1e-3), inclusionsMap(grid_n), built.L, {1100, 2700},
                            o);
  const Matrix6 C_ref = h.run().C.matrix();
  const double scale = C_ref.cwiseAbs().maxCoeff();
  EXPECT_LT((C - C_ref).cwiseAbs().maxCoeff(), 1e-10 * scale);
  EXPECT_LT((m.C - C_ref).cwiseAbs().maxCoeff(), 1e-10 * scale);
  // the cell is not a trivial one: its C is far from either phase's
  EXPECT_GT((C_ref - built.L[0].matrix()).cwiseAbs().maxCoeff(), 0.05 * scale);
}

TEST_P(ReducedOrderIdentities, MicroInertiaSumsFollowFromSumOfSEqualsMinusH) {
  const Built built = build(GetParam(), 2700);
  const materials::ReducedOrderModel& m = built.r.model;
  const Eigen::Index n6 = m.R.rows();
  // R: a Gram matrix of the S fields under the positive trilinear mass
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m.R);
  const double top = eig.eigenvalues().maxCoeff();
  ASSERT_GT(top, 0);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * top);
  EXPECT_LT((m.R - m.R.transpose()).cwiseAbs().maxCoeff(), 1e-15 * top);
  // sum_ab R^(ab)_kk = rho <H_k . H_k> = rho H_rms_k^2 (the dispersion's diagnostic)
  ASSERT_TRUE(built.r.dispersion.has_value());
  for (int k = 0; k < 6; ++k) {
    double sum = 0;
    for (Eigen::Index a = k; a < n6; a += 6)
      for (Eigen::Index b = k; b < n6; b += 6)
        sum += m.R(a, b);
    const double H2 = m.density * std::pow(built.r.dispersion->H_rms[static_cast<std::size_t>(k)], 2);
    EXPECT_NEAR(sum, H2, 1e-8 * H2) << k;
  }
}

TEST_P(ReducedOrderIdentities, OneDensityGivesQAndRSumsEqualToDlin) {
  const Built built = build(GetParam(), 1100); // both phases 1100 kg/m^3: h = H
  const materials::ReducedOrderModel& m = built.r.model;
  const Eigen::Index n6 = m.R.rows();
  Matrix6 sumQ = Matrix6::Zero(), sumR = Matrix6::Zero();
  for (Eigen::Index a = 0; a < n6; a += 6) {
    sumQ += m.Q.block<6, 6>(0, a);
    for (Eigen::Index b = 0; b < n6; b += 6)
      sumR += m.R.block<6, 6>(a, b);
  }
  const double D = m.D_lin.cwiseAbs().maxCoeff();
  ASSERT_GT(D, 0);
  EXPECT_LT((sumQ + m.D_lin).cwiseAbs().maxCoeff(), 1e-8 * D) << sumQ << "\nD_lin\n" << m.D_lin;
  EXPECT_LT((sumR - m.D_lin).cwiseAbs().maxCoeff(), 1e-8 * D) << sumR << "\nD_lin\n" << m.D_lin;
}

INSTANTIATE_TEST_SUITE_P(OneAndThreePerPhase, ReducedOrderIdentities, ::testing::Values(0, 3));

} // namespace
} // namespace lamina::test
