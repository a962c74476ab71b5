// Outputs of a large-deflection explicit run: the deformed surface in the
// XDMF series, the fabric's element fields, the summary's new keys.
#include "helpers.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

using namespace lamina::membrane;

// A square pulled at constant speed by its right edge (every node of it at
// 1 m/s along +x, the left edge fixed): after t the right edge has moved t
// exactly (a prescribed velocity integrated by the explicit scheme), so the
// peak displacement is t_end; the fabric is stretched along x, fails by
// strain, and the reactions balance (left + right = ma, small).
TEST(FabricOutputs, RunWritesTheDeformedSurfaceAndTheFabricFields) {
  Model m = test::modelFromText(R"(
name = "pull"
model = "large_deflection"
[mesh]
Lx = 1.0
nx = 4
[[section]]
E = 1.0e6
nu = 0.3
density = 1000.0
thickness = 1.0e-3
tension_only = true
failure_strain = 0.01
[time]
t_end = 0.05
[[fixed]]
name = "left"
nodes = "left"
[[strike]]
name = "right"
nodes = "right"
speed = 1.0
direction = [1.0, 0.0, 0.0]
[output]
field_every = 20
)");
  RunOptions opt;
  opt.out_dir = test::tempPath("lamina-fabric-outputs");
  opt.quiet = true;
  std::filesystem::remove_all(opt.out_dir);
  const auto s = runModel(m, opt);
  EXPECT_EQ(s["model"], "large_deflection");
  EXPECT_EQ(s["integrator"]["name"], "explicit");
  EXPECT_NEAR(s["integrator"]["safety"].get<double>(), 0.9, 1e-12);
  // The last step ends at or just after t_end (within one step).
  EXPECT_NEAR(s["max_displacement"].get<double>(), s["t_end"].get<double>(), 1e-12);
  EXPECT_GE(s["t_end"].get<double>(), 0.05 - 1e-12);
  // E11 = ((1 + t)^2 - 1) / 2 reaches 0.01 at t = sqrt(1.02) - 1 = 0.00995 for the
  // uniform stretch; the first element fails no later (the pulled edge's
  // elements stretch first in the dynamic run).
  ASSERT_TRUE(s.contains("failure"));
  EXPECT_EQ(s["failure"]["criterion"], "strain");
  EXPECT_LE(s["failure"]["time"].get<double>(), std::sqrt(1.02) - 1 + 1e-12);
  EXPECT_GT(s["peak_reaction_total"].get<double>(), 0.0);
  std::ifstream x(opt.out_dir / "pull.xdmf");
  const std::string xdmf((std::istreambuf_iterator<char>(x)), std::istreambuf_iterator<char>());
  for (const char* k : {"/steps/1/geometry", "principal_stress", "principal_strain", "wrinkled",
                        "failure_time", "displacement"})
    EXPECT_NE(xdmf.find(k), std::string::npos) << k;
  std::filesystem::remove_all(opt.out_dir);
}
