// Newmark with springs to the ground and rigid sets (issue 22): the same
// answers as central differences at small steps, and the exact discrete
// solution of a mass on a spring.
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace lamina::membrane;

namespace {

/// The z history of nodes @p probes (nearest to the points) over a run of @p text.
std::vector<std::vector<double>> zHistory(const std::string& text,
                                          const std::vector<Eigen::Vector2d>& probes) {
  Model m = test::modelFromText(text);
  Simulation sim(m);
  std::vector<std::vector<double>> w(probes.size());
  const double dt = sim.integrator().timeStep();
  while (sim.time() < m.time.t_end - 0.5 * dt) {
    sim.step();
    for (size_t k = 0; k < probes.size(); ++k)
      w[k].push_back(sim.u()[3 * m.mesh.nearestNode(probes[k]) + 2]);
  }
  return w;
}

/// Runs @p body (case keys after [time]) with both schemes at dt0 and dt0 / 2
/// and expects the O(dt^2) convergence of their difference at the probes:
/// both schemes are second order with the same (lumped) mass, so the
/// difference falls by ~4 when dt halves (accepted 3 to 5, as for the
/// schemes without springs in large_deflection_test.cpp) and is below 1 %
/// of the amplitude at the smaller step.
void expectSchemesAgree(const std::string& body, const std::vector<Eigen::Vector2d>& probes) {
  double diff[2] = {0, 0}, amp = 0;
  const double dt0 = 2.0e-5; // about 1/3 of the stable step (6.2e-5 s)
  for (int k = 0; k < 2; ++k) {
    const std::string dt = lamina::core::formatExact(dt0 / (1 << k));
    const std::string head = test::isotropicSquare(10) + "[time]\nt_end = 4.0e-3\ndt = " + dt;
    const auto we = zHistory(head + "\nintegrator = \"explicit\"\n" + body, probes);
    const auto wn = zHistory(head + "\nmass = \"lumped\"\n" + body, probes);
    for (size_t p = 0; p < probes.size(); ++p) {
      ASSERT_EQ(we[p].size(), wn[p].size());
      for (size_t i = 0; i < we[p].size(); ++i) {
        diff[k] = std::max(diff[k], std::abs(we[p][i] - wn[p][i]));
        amp = std::max(amp, std::abs(wn[p][i]));
      }
    }
  }
  EXPECT_GT(diff[0] / diff[1], 3.0);
  EXPECT_LT(diff[0] / diff[1], 5.0);
  EXPECT_LT(diff[1], 0.01 * amp);
}
} // namespace

// Springs on every node's z (k / m = 1e7 1/s^2 on an interior node of
// 0.01 kg: a frequency of the order of the (1,1) mode's), edges clamped.
TEST(NewmarkSystem, NewmarkWithSpringsEqualsCentralDifferences) {
  expectSchemesAgree(R"([[fixed]]
nodes = "edges"
[[spring]]
all = true
components = "z"
stiffness = 1.0e5
[initial]
mode = [1, 1]
mode_velocity = 1.0
)",
                     {{0.5, 0.5}, {0.3, 0.7}});
}

// The right edge translates as one body in z (a rigid set), the left edge
// is clamped, top and bottom free; the right edge's motion and the centre's.
TEST(NewmarkSystem, NewmarkWithARigidSetEqualsCentralDifferences) {
  expectSchemesAgree("[[fixed]]\nnodes = \"left\"\n" + test::rigidOnSprings("right", 1.0e4) +
                         R"([initial]
mode = [1, 1]
mode_velocity = 1.0
)",
                     {{0.5, 0.5}, {1.0, 0.5}, {1.0, 0.0}});
}

// A mass on a spring: every node tied into one rigid set in z (total mass
// m = rho h L^2 = 1 kg, consistent mass) on springs k = 1000 N/m each (121
// nodes: K = 1.21e5 N/m); from u = 0 at speed V the set oscillates at
// omega = sqrt(K / m). The average-acceleration rule is the Cayley map of
// the oscillator: (omega u_n, v_n) turns by theta = 2 atan(omega dt / 2)
// per step, so u_n = V / omega sin(n theta) exactly (asserted to 1e-9 of
// the amplitude: Cholesky solves, round-off of 360 steps), and it differs
// from V / omega sin(omega t_n) by the phase error n (omega dt)^3 / 12 at
// most (asserted with 10 % margin; 1.3e-3 rad here). The membrane's K does
// not act (a uniform translation has no strain), and the energy balance
// with the spring work is round-off (the rule's energy identity).
TEST(NewmarkSystem, MassOnASpringOscillatesAtSqrtKOverM) {
  const double V = 0.1, k = 1000.0, dt = 1.0e-4;
  Model m = test::modelFromText(test::isotropicSquare(10) +
                                "[time]\ndt = 1.0e-4\nt_end = 0.036\n[solver]\ntype = "
                                "\"cholesky\"\n[[rigid]]\nall = true\ncomponents = \"z\"\n"
                                "[[spring]]\nall = true\ncomponents = \"z\"\nstiffness = 1000.0\n"
                                "[initial]\nvelocity = [0.0, 0.0, 0.1]\n");
  const int nodes = m.mesh.numNodes();
  ASSERT_EQ(nodes, 121);
  const double omega = std::sqrt(nodes * k / 1.0);
  const double theta = 2 * std::atan(0.5 * omega * dt), amp = V / omega;
  Simulation sim(m);
  double worst_discrete = 0, worst_exact = 0, worst_spread = 0, worst_balance = 0, spring = 0;
  long n = 0;
  while (sim.time() < m.time.t_end - 0.5 * dt) {
    sim.step();
    ++n;
    const double uz = sim.u()[3 * 60 + 2];
    worst_discrete = std::max(worst_discrete, std::abs(uz - amp * std::sin(n * theta)));
    worst_exact = std::max(worst_exact, std::abs(uz - amp * std::sin(omega * sim.time())));
    for (int i = 0; i < nodes; ++i)
      worst_spread = std::max(worst_spread, std::abs(sim.u()[3 * i + 2] - uz));
    const Energy e = sim.energy();
    worst_balance = std::max(worst_balance, std::abs(e.balance));
    spring = std::max(spring, -e.spring_work);
  }
  ASSERT_EQ(n, 360);
  EXPECT_LT(worst_discrete, 1e-9 * amp);
  const double phase = static_cast<double>(n) * std::pow(omega * dt, 3) / 12;
  EXPECT_LT(worst_exact, 1.1 * amp * phase);
  EXPECT_EQ(worst_spread, 0.0); // one acceleration: the set's DOFs stay equal
  // The balance with the spring work, every step; at the turning points the
  // spring holds the whole initial energy (K u_max^2 / 2 = m V^2 / 2; the
  // steps sample the peak within (omega tau)^2 / 8 = 1.5e-4 of it).
  const double e0 = sim.initialEnergy();
  EXPECT_LT(worst_balance, 1e-9 * e0);
  EXPECT_GT(spring, (1 - 2e-4) * e0);
  EXPECT_LT(spring, (1 + 1e-9) * e0);
}
