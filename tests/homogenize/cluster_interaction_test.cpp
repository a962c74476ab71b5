/// @file cluster_interaction_test.cpp
/// @brief The interaction tensors of clustering analysis
/// (homogenize/cluster_interaction.hpp), summed in closed form over Fourier
/// modes, against the conjugate-gradient solves of the transformation
/// scheme's influence functions on the same partitions.
///
/// In a cell whose phases all have the one isotropic stiffness C0, a unit
/// eigenstrain mu on partition alpha is the polarization tau = -C0 mu there,
/// so the mean strain of partition beta is G^(beta alpha) C0 mu: the
/// builder's P^(beta alpha), from periodic solves, must equal G C0 with G =
/// (Ga - beta0 Gb) / mu0. Two independent routes to the same numbers (the
/// solver's stencil and CG against the symbol of the rotated scheme),
/// agreeing to the CG tolerance.

#include "homogenize/cluster_interaction.hpp"
#include "homogenize/reduced_order_builder.hpp"
#include "reduced_order_cells.hpp"

#include <gtest/gtest.h>

namespace lamina::test {
namespace {

using materials::Matrix6;

TEST(ClusterInteraction, HomogeneousCellGivesTheSolvedInfluenceFunctions) {
  const std::array<int, 3> n{8, 8, 8};
  const double E = 5e9, nu = 0.3;
  // four phases of one stiffness, one partition each: the inclusions' map
  // cut by the plane x = 3/8 into irregular pieces without symmetry
  std::vector<std::int32_t> map = inclusionsMap(n);
  for (std::size_t v = 0; v < map.size(); ++v)
    map[v] += v < 3 * 64 ? 2 : 0; // C order: x is the slowest index
  std::vector<materials::ReducedOrderPhase> phases;
  for (const char* name : {"a", "b", "c", "d"})
    phases.push_back(isotropicPhase(name, E, nu, 1000));
  homogenize::ReducedOrderOptions opt;
  opt.tol = 1e-12;
  opt.threads = 1;
  opt.scheme = materials::ReducedOrderScheme::Clustering;
  const homogenize::Grid grid = cubeGrid(n, 1e-3);
  homogenize::ReducedOrderBuilder b(grid, map, phases, false, opt);
  const homogenize::ReducedOrderResult r = b.run();
  const materials::ReducedOrderModel& m = r.model;
  const std::size_t np = static_cast<std::size_t>(m.partitions());
  ASSERT_EQ(np, 4u);
  ASSERT_EQ(m.Ga.size(), np * np);
  const double lambda0 = E * nu / ((1 + nu) * (1 - 2 * nu)), mu0 = E / (2 * (1 + nu));
  const Matrix6 C0 = materials::Stiffness::fromLame(lambda0, mu0).matrix();
  const double beta0 = (lambda0 + mu0) / (lambda0 + 2 * mu0);
  // P is a strain per unit strain (entries of order 0.1-1): the solves' CG
  // tolerance 1e-12 and round-off leave 1e-10 with margin; a wrong factor
  // 2 on a shear row or column, a sign or a transposition shows at 1e-2
  double worst = 0;
  for (std::size_t I = 0; I < np; ++I)
    for (std::size_t J = 0; J < np; ++J) {
      const Matrix6 G = (m.Ga[I * np + J] - beta0 * m.Gb[I * np + J]) / mu0;
      const double d = (G * C0 - m.P[I * np + J]).cwiseAbs().maxCoeff();
      worst = std::max(worst, d);
      EXPECT_LT(d, 1e-10) << "partitions " << I << ", " << J << "\nG C0\n"
                          << G * C0 << "\nP\n"
                          << m.P[I * np + J];
    }
  EXPECT_GT(m.P[0].cwiseAbs().maxCoeff(), 1e-2); // the comparison is not of zeros
  // a periodic strain has zero mean: sum_I c_I G^(IJ) = 0, to round-off of
  // entries of order one
  for (std::size_t J = 0; J < np; ++J) {
    Matrix6 sa = Matrix6::Zero(), sb = Matrix6::Zero();
    for (std::size_t I = 0; I < np; ++I) {
      sa += m.fraction[I] * m.Ga[I * np + J];
      sb += m.fraction[I] * m.Gb[I * np + J];
    }
    EXPECT_LT(sa.cwiseAbs().maxCoeff(), 1e-13) << J;
    EXPECT_LT(sb.cwiseAbs().maxCoeff(), 1e-13) << J;
  }
}

} // namespace
} // namespace lamina::test
