/// @file reduced_order_elastic_limit_test.cpp
/// @brief Elastic limits of the reduced-order law: a cell whose partitions
/// are all linear is linear elasticity with C = sum c L A (stress and
/// tangent, exactly), and the instantaneous stiffness of a GVBO cell is sum
/// c L0 A at J = 1 and, for a laminate, the exact laminate stiffness of the
/// layers' moduli at any J.

#include "reduced_order_cells.hpp"

#include "materials/reduced_order_law.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

namespace lamina {
namespace {

namespace mat = materials;
using mat::Matrix6;
using mat::Vector6;

/// sum c_a L_a A^(a) of @p m, L_a the partition's phase stiffness at J = 1.
Matrix6 averagedStiffness(const mat::ReducedOrderModel& m) {
  Matrix6 C = Matrix6::Zero();
  for (std::size_t a = 0; a < m.fraction.size(); ++a)
    C += m.fraction[a] * m.phases[static_cast<std::size_t>(m.partition_phase[a])].law.C.matrix() *
         m.A[a];
  return C;
}

mat::LawSpec anisotropic(const Matrix6& C) {
  mat::LawSpec s;
  s.kind = mat::LawKind::Anisotropic;
  s.C = mat::Stiffness(C);
  return s;
}

// Three triclinic layers: linear, no state, and stress and tangent are
// (sum c L A) eps and sum c L A to round-off (1e-12 relative: a handful of
// 6x6 products and sums of numbers of one sign scale).
TEST(ReducedOrderElasticLimit, AllLinearPartitionsGiveSumCLA) {
  std::mt19937_64 rng(3);
  const mat::ReducedOrderModel m =
      test::laminateCell({anisotropic(test::randomSpd(rng)), anisotropic(test::randomSpd(rng)),
                          anisotropic(test::randomSpd(rng))},
                         {0, 1, 2}, {0.5, 0.3, 0.2}, true);
  const mat::ReducedOrderLaw law("elastic-cell", m);
  EXPECT_TRUE(law.isLinear());
  EXPECT_EQ(law.stateSize(), 0);
  const Matrix6 C = averagedStiffness(m);
  // the identity sum c A = I of any cell holds for the oracle's A
  Matrix6 sumA = Matrix6::Zero();
  for (std::size_t a = 0; a < 3; ++a)
    sumA += m.fraction[a] * m.A[a];
  EXPECT_LE((sumA - Matrix6::Identity()).cwiseAbs().maxCoeff(), 1e-13);
  std::uniform_real_distribution<double> u(-1e-2, 1e-2);
  for (int trial = 0; trial < 5; ++trial) {
    mat::PointStep step;
    for (int i = 0; i < 6; ++i) {
      step.eps_n[i] = u(rng);
      step.eps[i] = u(rng);
    }
    step.dt = 1e-3;
    Vector6 sigma;
    Matrix6 T;
    law.update(step, nullptr, nullptr, sigma, &T);
    const Vector6 expect = C * step.eps;
    EXPECT_LE((sigma - expect).cwiseAbs().maxCoeff(), 1e-12 * expect.cwiseAbs().maxCoeff());
    EXPECT_LE(test::relDiff(T, C), 1e-12);
  }
  EXPECT_LE(test::relDiff(law.elasticStiffness(0.8).matrix(), C), 1e-12);
}

// A GVBO + elastic laminate is not linear; at J = 1 its instantaneous
// stiffness is sum c L0 A (every partition tangent is L0, so d mu = 0).
TEST(ReducedOrderElasticLimit, InstantaneousStiffnessAtJ1IsSumCL0A) {
  const mat::ReducedOrderModel m = test::polyureaLaminate();
  const mat::ReducedOrderLaw law("polyurea-laminate", m);
  EXPECT_FALSE(law.isLinear());
  EXPECT_LE(test::relDiff(law.elasticStiffness(1.0).matrix(), averagedStiffness(m)), 1e-12);
  EXPECT_LE(test::relDiff(law.elasticStiffness(1.0).matrix(), m.C), 1e-12);
}

// Away from J = 1 the GVBO moduli change (eqs. 13-16) while A and P stay
// those of L0 (eq. 27): the eigenstrains carry the change, and for a laminate
// the result is the exact laminate stiffness of the layers' moduli at J (the
// oracle run with L(J)). 1e-10: the 12 x 12 solve of the reduced system
// amplifies round-off by its condition number, about K / G of the soft phase
// times the stiffness contrast (83 x 6).
TEST(ReducedOrderElasticLimit, InstantaneousStiffnessAtJIsTheLaminateOfLJ) {
  const mat::ReducedOrderModel m = test::polyureaLaminate();
  const mat::ReducedOrderLaw law("polyurea-laminate", m);
  const mat::LawPtr soft = test::softGvbo().make(), hard = test::hardElastic().make();
  for (double J : {0.8, 0.9, 0.97}) {
    const std::vector<Matrix6> L{soft->elasticStiffness(J).matrix(),
                                 hard->elasticStiffness(J).matrix()};
    std::vector<Matrix6> A, P;
    test::laminateReducedOrder(L, m.fraction, A, P);
    const Matrix6 C = m.fraction[0] * L[0] * A[0] + m.fraction[1] * L[1] * A[1];
    EXPECT_GT(test::relDiff(C, m.C), 0.1) << "the moduli change at J = " << J;
    EXPECT_LE(test::relDiff(law.elasticStiffness(J).matrix(), C), 1e-10) << "J = " << J;
  }
}

} // namespace
} // namespace lamina
