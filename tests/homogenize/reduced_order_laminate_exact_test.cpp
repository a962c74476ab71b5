// The reduced-order build of a voxel laminate reproduces the exact
// strain concentration A^(alpha) and eigenstrain influence P^(beta alpha)
// of the classical laminate argument (tests/materials/laminate_reduced_order.hpp),
// one partition per layer.
//
// Why exactly: in a z-normal laminate the right-hand sides and the
// preconditioner are invariant under x and y translations, so every CG
// iterate depends on z alone. The voxel strain of such a field is
// (u(k + 1) - u(k)) / h_z in the out-of-plane components and zero in the
// in-plane ones, and the nodal balance D^T sigma = 0 makes the out-of-plane
// tractions equal in adjacent voxels: the discrete solution is the
// piecewise-uniform laminate solution itself, with no discretization error.
// What remains is the CG residual (tol 1e-12 in the reference energy norm,
// relative to a unit strain over the cell; the strain error is at most that
// times sqrt of the stiffness contrast, ~10 here) and round-off: 1e-9 on
// entries of order one bounds both with margin.

#include "homogenize/reduced_order_builder.hpp"
#include "materials/law_spec.hpp"
#include "reduced_order_cells.hpp"
#include "../materials/laminate_reduced_order.hpp"

#include <gtest/gtest.h>

namespace lamina::test {
namespace {

using materials::Matrix6;

TEST(ReducedOrderLaminate, InfluenceFunctionsEqualTheExactLaminate) {
  const std::array<int, 3> n{4, 4, 8};
  // three layers: 2, 3 and 3 voxels thick; the third is transversely
  // isotropic about x, so in- and out-of-plane components couple
  const std::vector<std::int32_t> layer_of{0, 0, 1, 1, 1, 2, 2, 2};
  const materials::Stiffness ti = materials::transverselyIsotropic(60e9, 8e9, 4e9, 0.3, 0.4);
  const std::vector<materials::ReducedOrderPhase> phases{
      isotropicPhase("soft", 3e9, 0.4, 1100), isotropicPhase("stiff", 70e9, 0.25, 2700),
      elasticPhase("fibrous", ti, 1600, materials::LawKind::TransverselyIsotropic)};
  homogenize::ReducedOrderOptions opt;
  opt.tol = 1e-12;
  opt.threads = 1;
  homogenize::ReducedOrderBuilder b(cubeGrid(n, 1e-3), laminateMap(n, layer_of), phases, false,
                                    opt);
  const homogenize::ReducedOrderResult r = b.run();
  const materials::ReducedOrderModel& m = r.model;
  ASSERT_EQ(m.partitions(), 3);
  std::vector<Matrix6> L;
  for (const auto& p : phases)
    L.push_back(p.law.C.matrix());
  const std::vector<double> c{2.0 / 8, 3.0 / 8, 3.0 / 8};
  std::vector<Matrix6> A, P;
  laminateReducedOrder(L, c, A, P);
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_NEAR(m.fraction[a], c[a], 1e-15) << a;
    EXPECT_LT((m.A[a] - A[a]).cwiseAbs().maxCoeff(), 1e-9) << "A of layer " << a << "\n"
                                                           << m.A[a] << "\nexact\n"
                                                           << A[a];
    for (std::size_t b2 = 0; b2 < 3; ++b2)
      EXPECT_LT((m.P[b2 * 3 + a] - P[b2 * 3 + a]).cwiseAbs().maxCoeff(), 1e-9)
          << "P of layers " << b2 << ", " << a << "\n"
          << m.P[b2 * 3 + a] << "\nexact\n"
          << P[b2 * 3 + a];
  }
  // the oracle itself is not trivial: the layers' A differ from I and from each other
  EXPECT_GT((A[0] - A[1]).cwiseAbs().maxCoeff(), 0.5);
}

} // namespace
} // namespace lamina::test
