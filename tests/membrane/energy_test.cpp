// Energy identities of the Newmark scheme (eq. 30), reactions, divergence.
#include "helpers.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

using namespace lamina::membrane;

namespace {
const double kPi = 3.14159265358979323846;

std::string anisotropicSquare(const std::string& solver, const std::string& extra = "") {
  return R"(
[mesh]
Lx = 0.2
nx = 10
[[section]]
material = "table1-anisotropic"
thickness = 1.0e-3
[time]
dt = 2.0e-6
t_end = 2.0e-3
[solver]
type = ")" +
         solver + R"("
tolerance = 1.0e-14
[[fixed]]
nodes = "edges"
)" + extra;
}

/// u0 = smooth in-plane and out-of-plane bumps vanishing on the edges.
void setBumps(Model& m) {
  const int n = m.mesh.numNodes();
  m.u0 = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i) {
    const double x = m.mesh.nodes[i].x() / 0.2, y = m.mesh.nodes[i].y() / 0.2;
    const double s = std::sin(kPi * x) * std::sin(kPi * y);
    m.u0[3 * i] = 1e-5 * s;
    m.u0[3 * i + 1] = -2e-5 * s * x;
    m.u0[3 * i + 2] = 1e-4 * s;
  }
}
} // namespace

TEST(MembraneEnergy, ConservedToRoundOffOver1000StepsWithoutLoad) {
  for (const char* solver : {"cholesky", "cg"}) {
    Model m = test::modelFromText(anisotropicSquare(solver));
    setBumps(m);
    Simulation sim(m);
    const double e0 = sim.initialEnergy();
    ASSERT_GT(e0, 0);
    double worst = 0;
    for (int s = 0; s < 1000; ++s) {
      sim.step();
      worst = std::max(worst, std::abs(sim.energy().balance));
    }
    // Average acceleration conserves T + U exactly; 1000 steps of round-off
    // (~1e-16 each; CG run to 1e-14 relative residual) stay below 1e-11 E0.
    EXPECT_LT(worst, 1e-11 * e0) << solver;
  }
}

TEST(MembraneEnergy, BalanceHoldsWithLoadsAndAMovingStrike) {
  // Force pulse, pressure table and a strike whose speed ramps (non-zero
  // prescribed acceleration) at once: E_n - E_0 - W_n stays at round-off.
  const std::string extra = R"(
[[strike]]
at = [0.1, 0.1]
speed = 3.0
direction = [0.3, -0.2, 1.0]
profile = "ramp"
rise = 2.0e-4
[[load]]
type = "force"
value = 50.0
inclination_deg = 30.0
box = [0.02, 0.06, 0.02, 0.06]
profile = "pulse"
t0 = 1.0e-4
duration = 3.0e-4
[[load]]
type = "pressure"
value = 2000.0
profile = "table"
table = [[0.0, 0.0], [5.0e-4, 1.0], [1.0e-3, -0.5]]
)";
  for (const char* solver : {"cholesky", "cg"}) {
    Model m = test::modelFromText(anisotropicSquare(solver, extra));
    Simulation sim(m);
    test::BalanceTracker b;
    for (int s = 0; s < 1000; ++s) {
      sim.step();
      b.add(sim.energy());
    }
    ASSERT_GT(b.scale, 0);
    // Exact identity of the trapezoidal works under average acceleration.
    EXPECT_LT(b.worst, 1e-10 * b.scale) << solver;
  }
}

TEST(MembraneEnergy, ReactionsCloseTheMomentumBalance) {
  // d/dt (total momentum) = sum F + sum R, i.e. sum(M a) = sum F + sum R per component.
  const std::string extra = R"(
[[strike]]
at = [0.1, 0.1]
speed = 3.0
[[load]]
type = "pressure"
value = 1000.0
)";
  Model m = test::modelFromText(anisotropicSquare("cholesky", extra));
  Simulation sim(m);
  for (int s = 0; s < 50; ++s)
    sim.step();
  const Eigen::VectorXd Ma = sim.M() * sim.a();
  Eigen::Vector3d lhs = Eigen::Vector3d::Zero(), rhs = Eigen::Vector3d::Zero();
  for (int i = 0; i < m.mesh.numNodes(); ++i)
    lhs += Ma.segment<3>(3 * i);
  for (const auto& r : sim.reactionSums())
    rhs += r;
  rhs.z() += 1000.0 * 0.2 * 0.2;
  EXPECT_LT((lhs - rhs).norm(), 1e-9 * rhs.norm());
}

TEST(MembraneEnergy, HhtAlphaDissipatesAndDefaultDoesNot) {
  Model m = test::modelFromText(anisotropicSquare("cholesky"));
  std::string hs = anisotropicSquare("cholesky");
  hs.insert(hs.find("t_end"), "hht_alpha = -0.2\n");
  Model h = test::modelFromText(hs);
  setBumps(m);
  setBumps(h);
  Simulation a(m), b(h);
  for (int s = 0; s < 300; ++s) {
    a.step();
    b.step();
  }
  const Energy ea = a.energy(), eb = b.energy();
  EXPECT_LT(std::abs(ea.balance), 1e-11 * a.initialEnergy());
  // HHT removes energy from the resolved high modes: a clear loss (> 1e-4 E0).
  EXPECT_LT(eb.balance, -1e-4 * b.initialEnergy());
}

TEST(MembraneRun, NonFiniteStateStopsWithLastFiniteStateWritten) {
  // beta2 = 0 is explicit; dt far above its stability limit blows up.
  Model m = test::modelFromText(test::isotropicSquare(8) + R"(
[time]
dt = 1.0
t_end = 1000.0
beta2 = 0.0
[[fixed]]
nodes = "edges"
[[strike]]
at = [0.5, 0.5]
speed = 1.0
[output]
field_every = 0
)");
  RunOptions opt;
  opt.out_dir = test::tempPath("lamina-membrane-diverge");
  opt.quiet = true;
  std::filesystem::remove_all(opt.out_dir);
  EXPECT_THROW(runModel(m, opt), lamina::DivergenceError);
  std::ifstream in(opt.out_dir / "summary.json");
  ASSERT_TRUE(in.good());
  const auto s = nlohmann::json::parse(in);
  EXPECT_TRUE(s.contains("diverged"));
  EXPECT_NE(s["diverged"].get<std::string>().find("node"), std::string::npos);
  EXPECT_TRUE(std::isfinite(s["max_abs_w"].get<double>()));
  EXPECT_LT(s["steps"].get<long>(), 1000);
  EXPECT_TRUE(std::filesystem::exists(opt.out_dir / "probes.csv"));
  std::filesystem::remove_all(opt.out_dir);
}
