// The convergence study of section 4 on case 3.
#include "helpers.hpp"
#include "membrane/converge.hpp"

#include <gtest/gtest.h>

using namespace lamina::membrane;

TEST(MembraneConvergence, ObservedRateOfAnExactPowerLawIsItsExponent) {
  EXPECT_NEAR(observedRate({1.0, 0.25, 0.0625}), 2.0, 1e-12);
}

TEST(MembraneConvergence, Case3WithFinitePatchAndRampConvergesAtOrderOneAndAHalf) {
  // case3-patch.toml: case 3 with a 0.2 m striker patch and a 0.2 ms ramp, so
  // that a continuum limit exists (see the next test and docs/membrane.md).
  // Grids 10, 20, 40, 80 squares, tau halved with h.
  const auto study = runConvergence(test::sourcePath("cases/membrane/case3-patch.toml"), {},
                                    test::testSources(), 4);
  // The scheme is second order (beta1 = 1/2); the patch corners lower the
  // observed order. Required by the paper's claim for case 3: >= 1.5 (L1).
  EXPECT_GE(study.rate_u[0], 1.5);
  EXPECT_GE(study.rate_u[1], 1.4);
}

TEST(MembraneConvergence, Case3PointStrikeConverges) {
  // The literal case 3 (one node at constant speed from t = 0). Its
  // differences shrink with refinement (rate > 0.5), but a single node in 2D
  // has zero capacity, so the order stays near 1 (measured 0.92 in L1 on
  // grids 10-80), not the paper's 2.0.
  const auto study = runConvergence(test::sourcePath("cases/membrane/case3.toml"),
                                    {"mesh.nx=10", "time.dt=2e-5"}, test::testSources(), 4);
  EXPECT_GT(study.rate_u[0], 0.5);
}
