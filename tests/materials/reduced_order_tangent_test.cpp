/// @file reduced_order_tangent_test.cpp
/// @brief The coarse tangent of the reduced-order law is consistent: it
/// equals central differences of update() on a GVBO + elastic laminate after
/// a viscous loading, at three time steps.

#include "reduced_order_cells.hpp"

#include "materials/reduced_order_law.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

namespace lamina {
namespace {

namespace mat = materials;
using mat::Matrix6;
using mat::Vector6;

// Loaded in tension (every partition's J > 1, where the GVBO moduli stay at
// their initial values, eqs. 13-16, so the J held fixed by the GVBO tangent
// does not matter), then one more step at dt = 1e-5, 1e-2 and 1 s. Bound
// 1e-6 of max |C_T|: central differences with h = 1e-8 on strains of 1e-2
// have truncation ~h^2 and round-off ~1e-16/h ~ 1e-8; the Newton runs to
// 1e-14 of the strain, so its noise in a difference is 1e-14 x 5e-2 / 1e-8 =
// 5e-8; 1e-6 leaves a factor 20 above both.
void expectConsistentTangent(const mat::ReducedOrderLaw& law) {
  Vector6 E;
  E << 0.05, 0.01, 0.03, 0.04, 0.01, -0.03;
  std::vector<double> state;
  const Vector6 eps = test::loadAlong(law, E, 10, 1e-2, state);
  Vector6 sigma;
  for (int a = 0; a < 2; ++a) {
    const Eigen::Map<const Vector6> ea(state.data() + law.stateOffset(a));
    ASSERT_GT(ea.head<3>().sum(), 1e-3) << "partition " << a << " is in tension (J > 1)";
  }
  Vector6 de;
  de << 0.002, -0.001, 0.0005, 0.003, -0.002, 0.001;
  for (double dt : {1e-5, 1e-2, 1.0}) {
    const mat::PointStep step{eps, eps + de, 1 + eps.head<3>().sum(),
                              1 + (eps + de).head<3>().sum(), dt};
    std::vector<double> out(state.size());
    Matrix6 T;
    law.update(step, state.data(), out.data(), sigma, &T);
    const Matrix6 Tfd = test::centralDifferenceTangent(law, step, state.data(), 1e-8);
    EXPECT_LE((T - Tfd).cwiseAbs().maxCoeff(), 1e-6 * T.cwiseAbs().maxCoeff())
        << "dt " << dt << "\nT\n"
        << T << "\nFD\n"
        << Tfd;
    // from dt = 1e-2 on the step is not elastic: the tangent has left the
    // instantaneous one (so the comparison sees the viscous terms)
    if (dt >= 1e-2) {
      EXPECT_GT((T - law.elasticStiffness(1.0).matrix()).cwiseAbs().maxCoeff(),
                1e-3 * T.cwiseAbs().maxCoeff())
          << "dt " << dt;
    }
  }
}

TEST(ReducedOrderTangent, MatchesCentralDifferencesOfUpdate) {
  expectConsistentTangent(
      mat::ReducedOrderLaw("polyurea-laminate", test::polyureaLaminate(), {1e-14, 25}));
}

// The clustering scheme: a step runs in the reference medium of the state
// (fitted at the end of the step before), so within the step the tangent
// is the exact derivative of update(), to the same bound.
TEST(ReducedOrderTangent, ClusteringMatchesCentralDifferencesOfUpdate) {
  expectConsistentTangent(mat::ReducedOrderLaw(
      "polyurea-laminate", test::clustering(test::polyureaLaminate()), {1e-14, 25}));
}

} // namespace
} // namespace lamina
