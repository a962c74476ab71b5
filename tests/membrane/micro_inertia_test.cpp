// Micro-inertia in the membrane (GVBO chapter eq. 35): the plane-wave
// dispersion relation omega^2 (rho + zeta^2 D k^2) = C k^2, the energy
// balance with the micro-kinetic term, the case keys.
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace lamina::membrane;

namespace {
const double kPi = 3.14159265358979323846;
const double E = 1e9, rho = 1000;

/// A strip [0, 1] x [0, 0.01] m of an isotropic section with nu = 0 (so
/// that u along x does not pull v: a 1D bar with C_xx = E) and dispersion
/// diag(dP, 0, 0, dS, dS, dS) (kg/m), u fixed at both ends.
/// Cholesky: with l = sqrt(zeta^2 D / rho) = 0.1 m, 45 elements long, the
/// step operator M + M_D + c K is a Laplacian-like matrix that block-Jacobi
/// CG needs hundreds of iterations for (docs/membrane.md).
std::string strip(int nx, double dP, double dS, double dt, const std::string& extra = "") {
  auto f = [](double x) { return lamina::core::formatExact(x); };
  return "[mesh]\nLx = 1.0\nLy = 0.01\nnx = " + std::to_string(nx) +
         "\nny = 1\n[[section]]\nE = 1.0e9\nnu = 0.0\ndensity = 1000.0\nthickness = 1.0e-3\n"
         "dispersion = [[" +
         f(dP) + ", 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, " + f(dS) +
         ", 0, 0], [0, 0, 0, 0, " + f(dS) + ", 0], [0, 0, 0, 0, 0, " + f(dS) + "]]\n" + extra +
         "[time]\ndt = " + f(dt) +
         "\nt_end = 1.0\n[solver]\ntype = \"cholesky\"\n"
         "[[fixed]]\nnodes = \"left\"\ncomponents = \"x\"\n"
         "[[fixed]]\nnodes = \"right\"\ncomponents = \"x\"\n";
}

/// The period of the standing P wave u = sin(k x), k = m pi, measured from
/// four zero crossings of u at x = 1/(2m).
double measuredPeriod(Model m, int mode) {
  const double k = mode * kPi;
  const int n = m.mesh.numNodes();
  m.u0 = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i)
    m.u0[3 * i] = 1e-6 * std::sin(k * m.mesh.nodes[i].x());
  const int probe = m.mesh.nearestNode({0.5 / mode, 0.0});
  Simulation sim(m);
  std::vector<double> crossings;
  double prev = sim.u()[3 * probe], tprev = 0;
  while (crossings.size() < 5) {
    sim.step();
    const double u = sim.u()[3 * probe];
    if ((prev > 0) != (u > 0))
      crossings.push_back(tprev + (sim.time() - tprev) * prev / (prev - u));
    prev = u;
    tprev = sim.time();
  }
  return (crossings[4] - crossings[0]) / 2;
}

// The standing wave of wavenumber k is a superposition of two plane waves
// of phase speed omega/k; with micro-inertia the model gives
// omega^2 = C k^2 / (rho + zeta^2 D k^2). The dispersion is chosen so that
// zeta^2 D k^2 / rho = 1/2 for mode 2 and 1/8 for mode 1 (and 2 for mode 4):
// periods 22 %, 6 % and 73 % above the classical ones. Tolerance: linear
// elements at h = 1/400 (k h <= 0.031) err by (k h)^2/12 <= 1e-4 in omega^2,
// average acceleration lengthens the period by (omega dt)^2/24 < 3e-5 with
// 400 steps per period: 5e-4 bounds both with room, and is 100 times smaller
// than the smallest effect checked.
TEST(MembraneMicroInertia, PlaneWaveFollowsTheDispersionRelation) {
  const double C = E;
  const double dP = 0.5 * rho / std::pow(2 * kPi, 2); // zeta^2 D (kg/m)
  for (int mode : {1, 2, 4}) {
    const double k = mode * kPi;
    const double omega = std::sqrt(C * k * k / (rho + dP * k * k));
    const double period = 2 * kPi / omega;
    const Model m = test::modelFromText(strip(400, dP, 0.0, period / 400));
    EXPECT_NEAR(measuredPeriod(m, mode) / period, 1.0, 5e-4) << "mode " << mode;
    // the classical speed is what the model gives with micro-inertia off
    const double classical = 2 * kPi / (std::sqrt(C / rho) * k);
    const Model off =
        test::modelFromText(strip(400, dP, 0.0, classical / 400, "micro_inertia = false\n"));
    EXPECT_NEAR(measuredPeriod(off, mode) / classical, 1.0, 5e-4) << "mode " << mode << ", off";
  }
}

// With micro-inertia the conserved energy is T + U with T = v.(M + M_D)v/2:
// a free vibration of a bumpy initial field in a square with all three
// components moving keeps it to round-off (1e-11 of E0 over 500 steps, as
// without micro-inertia), the micro-kinetic part v.M_D v/2 is reported, is
// positive and stays below T, and a strike's work closes the balance too.
TEST(MembraneMicroInertia, EnergyBalanceClosesWithTheMicroKineticTerm) {
  const std::string text = R"(
[mesh]
Lx = 0.2
nx = 16
[[section]]
E = 1.0e9
nu = 0.3
density = 1000.0
thickness = 1.0e-3
dispersion = [[0.02, 0.004, 0, 0, 0, 0], [0.004, 0.01, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0],
              [0, 0, 0, 0.015, 0, 0], [0, 0, 0, 0, 0.01, 0.002], [0, 0, 0, 0, 0.002, 0.012]]
[time]
dt = 2e-6
t_end = 1.0
[solver]
type = "cholesky"
[[fixed]]
nodes = "edges"
)";
  Model m = test::modelFromText(text);
  const int n = m.mesh.numNodes();
  m.u0 = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i) {
    const double x = m.mesh.nodes[i].x() / 0.2, y = m.mesh.nodes[i].y() / 0.2;
    const double s = std::sin(kPi * x) * std::sin(2 * kPi * y);
    m.u0[3 * i] = 1e-5 * s;
    m.u0[3 * i + 1] = -2e-5 * s * x;
    m.u0[3 * i + 2] = 1e-4 * s;
  }
  Simulation sim(m);
  const double e0 = sim.initialEnergy();
  ASSERT_GT(e0, 0);
  double worst = 0, micro = 0;
  for (int s = 0; s < 500; ++s) {
    sim.step();
    const Energy e = sim.energy();
    worst = std::max(worst, std::abs(e.balance));
    micro = std::max(micro, e.micro_kinetic);
    EXPECT_LE(e.micro_kinetic, e.kinetic * (1 + 1e-12));
  }
  EXPECT_LT(worst, 1e-11 * e0);
  EXPECT_GT(micro, 0);

  // a strike adds work: W = E - E0 at every step to round-off
  Model struck = test::modelFromText(text + R"(
[[strike]]
at = [0.1, 0.1]
speed = 1.0
profile = "ramp"
rise = 1e-4
)");
  Simulation sim2(struck);
  test::BalanceTracker b;
  for (int s = 0; s < 300; ++s) {
    sim2.step();
    b.add(sim2.energy());
  }
  EXPECT_GT(sim2.energy().micro_kinetic, 0);
  EXPECT_LT(b.worst, 1e-10 * b.scale);
}

// Keys: an inline dispersion must be 6x6, symmetric and positive
// semi-definite; a named material brings its own (an inline one is refused).
TEST(MembraneMicroInertia, BadDispersionKeysAreNamed) {
  auto error = [](const std::string& text) {
    try {
      test::modelFromText(text);
    } catch (const lamina::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string head =
      "[mesh]\nLx = 0.1\nnx = 2\n[time]\ndt = 1e-6\nt_end = 1e-5\n[[section]]\n";
  std::string msg = error(head + "E = 1e9\nnu = 0.3\ndensity = 1000.0\nthickness = 1e-3\n"
                                 "dispersion = [[1, 0], [0, 1]]\n");
  EXPECT_NE(msg.find("dispersion"), std::string::npos) << msg;
  EXPECT_NE(msg.find("6 rows"), std::string::npos) << msg;
  msg = error(head + "E = 1e9\nnu = 0.3\ndensity = 1000.0\nthickness = 1e-3\n"
                     "dispersion = [[-1, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], "
                     "[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]\n");
  EXPECT_NE(msg.find("section[0].dispersion"), std::string::npos) << msg;
  EXPECT_NE(msg.find("semi-definite"), std::string::npos) << msg;
  msg = error(head + "material = \"e-glass\"\nthickness = 1e-3\n"
                     "dispersion = [[1, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], "
                     "[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]\n");
  EXPECT_NE(msg.find("only with an inline material"), std::string::npos) << msg;
}
} // namespace
