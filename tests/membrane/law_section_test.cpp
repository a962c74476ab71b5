// Large-deflection membranes whose sections hold a nonlinear law (GVBO):
// the element against `materials drive` on the same path, the slow and the
// fast limits, the energy balance with the law's dissipation.
#include "helpers.hpp"

#include "materials/material_source.hpp"
#include "materials/point_driver.hpp"
#include "membrane/model/large_deflection.hpp"
#include "membrane/model/law_point.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace lamina::membrane {
namespace {

/// The catalog's GVBO polyurea (polyurea chapter, Table 5).
materials::LawPtr polyurea() {
  materials::MaterialSource src(test::testSources().library_path, test::testSources().catalog_path);
  return src.law("polyurea-gvbo");
}

/// A flat square of side 1 m (nx x nx squares) of polyurea, 1 mm, on the
/// large-deflection model, explicit; @p extra appended.
Model polyureaSquare(int nx, const std::string& extra) {
  Model m = test::modelFromText(
      "model = \"large_deflection\"\n[mesh]\nLx = 1.0\nnx = " + std::to_string(nx) +
      "\n[[section]]\nE = 278.0e6\nnu = 0.491\ndensity = 1100.0\n"
      "thickness = 1.0e-3\n[time]\nintegrator = \"explicit\"\n" +
      extra);
  m.sections[0].law = polyurea();
  m.sections[0].material = "polyurea-gvbo";
  return m;
}

// One element (every node prescribed) under the equibiaxial stretch
// F = diag(1 + e, 1 + e) at 1e2 /s to 0.2: the law's in-plane Cauchy stress
// and the thickness stretch equal `materials drive --path biaxial-stress`,
// which reaches sigma_zz = 0 by its own Newton on F (finiteIncrement of the
// 3x3 F) where the membrane solves the out-of-plane strain of the law's step.
// Both converge sigma_zz to ~1e-10 of the stress and share the midpoint rule,
// so 1e-8 of the peak stress leaves room only for round-off.
TEST(LawSection, SingleElementMatchesDriveOnTheBiaxialStressPath) {
  const double rate = 1e2, to = 0.2;
  const int steps = 100;
  const double dt = to / rate / steps;
  materials::DriveOptions o;
  o.path = materials::DrivePath::BiaxialStress;
  o.rate = rate;
  o.to = to;
  o.steps = steps;
  const auto rows = materials::drive(*polyurea(), o);
  ASSERT_EQ(rows.size(), static_cast<size_t>(steps + 1));
  Model m = polyureaSquare(1, "dt = " + core::formatExact(dt) + "\nt_end = 1.0\n");
  m.constraints = {test::uniformStretch(m.mesh, rate, rate)};
  Simulation sim(m);
  const auto& ld = dynamic_cast<const LargeDeflection&>(sim.structure());
  double peak = 0;
  for (const auto& r : rows)
    peak = std::max(peak, std::abs(r.sigma[0]));
  for (int n = 1; n <= steps; ++n) {
    sim.step();
    ASSERT_DOUBLE_EQ(sim.time(), rows[n].t);
    for (int e = 0; e < m.mesh.numElements(); ++e) {
      const double* b = ld.history(e);
      ASSERT_NE(b, nullptr);
      EXPECT_NEAR(b[LawPoint::kSigma], rows[n].sigma[0], 1e-8 * peak) << "step " << n;
      EXPECT_NEAR(b[LawPoint::kSigma + 1], rows[n].sigma[1], 1e-8 * peak) << "step " << n;
      EXPECT_NEAR(b[LawPoint::kSigma + 2], 0.0, 1e-8 * peak) << "step " << n;
      EXPECT_NEAR(b[LawPoint::kLambda3], 1 + rows[n].eps[2], 1e-8) << "step " << n;
    }
  }
}

// Wrinkling composes with the law: an element stretched along x at 1e2 /s
// while its y side shortens at the same rate wrinkles (the law's lateral
// contraction, about nu e, is less than e), so the law sees uniaxial stress:
// its stress along x equals `materials drive --path uniaxial-stress` at the
// same rate, the stress along y vanishes. Tolerance 1e-3 of the peak: the
// law's area ratio under wrinkles is taken as the element's times
// (2 - tr eps_w)/(2 + tr eps_w), exp(-tr eps_w) to third order in eps_w
// (~0.1 here: 1e-4 in J, whose effect on the moduli the drive has exactly).
TEST(LawSection, WrinkledElementCarriesTheLawsUniaxialStress) {
  const double rate = 1e2, to = 0.1;
  const int steps = 100;
  const double dt = to / rate / steps;
  materials::DriveOptions o;
  o.path = materials::DrivePath::UniaxialStress;
  o.rate = rate;
  o.to = to;
  o.steps = steps;
  const auto rows = materials::drive(*polyurea(), o);
  Model m = polyureaSquare(1, "dt = " + core::formatExact(dt) + "\nt_end = 1.0\n");
  m.sections[0].tension_only = true;
  m.constraints = {test::uniformStretch(m.mesh, rate, -rate)};
  Simulation sim(m);
  const auto& ld = dynamic_cast<const LargeDeflection&>(sim.structure());
  double peak = 0;
  for (const auto& r : rows)
    peak = std::max(peak, std::abs(r.sigma[0]));
  for (int n = 1; n <= steps; ++n) {
    sim.step();
    for (int e = 0; e < m.mesh.numElements(); ++e) {
      const double* b = ld.history(e);
      EXPECT_EQ(b[LawPoint::kWrinkleState], 1.0) << "step " << n;
      EXPECT_NEAR(b[LawPoint::kSigma], rows[n].sigma[0], 1e-3 * peak) << "step " << n;
      EXPECT_NEAR(b[LawPoint::kSigma + 1], 0.0, 1e-8 * peak) << "step " << n;
      EXPECT_NEAR(b[LawPoint::kSigma + 2], 0.0, 1e-8 * peak) << "step " << n;
    }
  }
}

// At a very high rate (1e5 /s to 1 %) the overstress has no time to relax:
// GVBO responds with its instantaneous moduli (E0, nu0 of Table 5). An
// element stretched along x (F = diag(1 + e, 1), membrane plane stress) by a
// hypoelastic law at those moduli has sigma_xx = E0 / (1 - nu0^2) m exactly,
// m = sum 2 d lambda / (lambda_n + lambda_{n+1}) the midpoint strain of the
// kinematics (J > 1 here, where the moduli of eqs. 13-16 stay at their
// initial values). The bound is 2 %; GVBO relaxes by 9e-7 of the
// stress in these 1e-7 s (measured), so 1e-4 still tells a relaxation of the
// elastic response from an error in the moduli or the kinematics.
TEST(LawSection, AtAVeryHighRateGvboHasItsInstantaneousModuli) {
  const double rate = 1e5, to = 0.01, dt = 1e-9, E0 = 278e6, nu0 = 0.491;
  const int steps = static_cast<int>(std::lround(to / rate / dt));
  Model g = polyureaSquare(1, "dt = 1.0e-9\nt_end = 1.0e-7\n");
  g.constraints = {test::uniformStretch(g.mesh, rate, 0.0)};
  Simulation sim(g);
  const auto& ld = dynamic_cast<const LargeDeflection&>(sim.structure());
  double m = 0;
  for (int n = 1; n <= steps; ++n) {
    sim.step();
    const double l0 = 1 + rate * (n - 1) * dt, l1 = 1 + rate * n * dt;
    m += 2 * (l1 - l0) / (l0 + l1);
  }
  const double expect = E0 / (1 - nu0 * nu0) * m;
  for (int e = 0; e < g.mesh.numElements(); ++e) {
    const double s = ld.history(e)[LawPoint::kSigma];
    EXPECT_LT(s, expect) << "relaxation only lowers the stress";
    EXPECT_NEAR(s / expect, 1.0, 1e-4) << "element " << e << ": " << s << " vs " << expect;
  }
}

// A free sheet pulled slowly (1e-3 /s to 3 %, an edge moving at 1 mm/s; the
// wave crosses the sheet in 2 ms, so the run is quasi-static): the force on
// the pulled edge per unit reference width is h0 sigma_xx lambda_y lambda_z of
// `materials drive --path uniaxial-stress` at the same rate (GVBO has no
// linear relaxed modulus: at 1e-3 /s its secant falls from 240 to 40 MPa
// between 0.1 % and 3 %, so the slow limit is the law's own slow curve).
// The bound is 2 %; measured 6.5e-3 at the first point (0.3 %, in
// the knee, with the start's dynamic transient still ringing), 2e-5 to
// 2.4e-4 after it: 1e-2.
TEST(LawSection, SlowlyPulledSheetFollowsTheLawsSlowCurve) {
  const double rate = 1e-3, to = 0.03, h0 = 1e-3;
  Model m = polyureaSquare(2, "safety = 0.5\nt_end = " + core::formatExact(to / rate) + "\n");
  Constraint left, right, pin;
  left.name = "left";
  right.name = "right";
  pin.name = "pin";
  for (int i = 0; i < m.mesh.numNodes(); ++i) {
    const Eigen::Vector3d p = m.mesh.point(i);
    pin.dofs.push_back(3 * i + 2); // flat: no z
    pin.amplitude.push_back(0);
    if (p.x() < 1e-12) {
      left.dofs.push_back(3 * i);
      left.amplitude.push_back(0);
      if (p.y() < 1e-12) {
        left.dofs.push_back(3 * i + 1);
        left.amplitude.push_back(0);
      }
    } else if (p.x() > 1 - 1e-12) {
      right.dofs.push_back(3 * i);
      right.amplitude.push_back(rate);
    }
  }
  m.constraints = {left, right, pin};
  materials::DriveOptions o;
  o.path = materials::DrivePath::UniaxialStress;
  o.rate = rate;
  o.to = to;
  o.steps = 300;
  const auto rows = materials::drive(*polyurea(), o);
  Simulation sim(m);
  size_t next = 30; // compare every 30 rows (0.3 %)
  while (next < rows.size()) {
    while (sim.time() < rows[next].t)
      sim.step();
    // the step (~1e-3 s) overshoots the row's time: the expected force is
    // carried to the step's time along the drive's slope
    const double t = sim.time();
    const auto& r = rows[next];
    const double force = sim.reactionSums()[1].x();
    const double expect = h0 * r.sigma[0] * (1 + r.eps[1]) * (1 + r.eps[2]);
    const double slope =
        (rows[next].sigma[0] - rows[next - 1].sigma[0]) / (rows[next].t - rows[next - 1].t) * h0;
    EXPECT_NEAR(force, expect + slope * (t - r.t), 1e-2 * expect) << "t = " << t;
    next += 30;
  }
}

// A GVBO sheet thrown at 10 m/s against its clamped edges: the energy
// balance T + U + D_in - W closes within 1e-3 of the work (the issue's
// bound), where D_in is the law's dissipation summed from its own history
// (law_point.hpp: the trapezoidal work over the law's strain) and W the work
// of the reactions summed from the nodal forces. The two quadratures of the
// same work differ at second order in dt: 3.5e-4 here at the default step;
// at 30 m/s 1.1e-3, and 3x less at half the step. D_in > 0 and grows.
TEST(LawSection, EnergyBalanceClosesWithTheInelasticDissipation) {
  Model m = polyureaSquare(8, "t_end = 4.0e-3\n[[fixed]]\nnodes = \"edges\"\n"
                              "[initial]\nvelocity = [0.0, 0.0, 10.0]\n");
  Simulation sim(m);
  double worst = 0, scale = 0, last_d = 0;
  while (sim.time() < m.time.t_end) {
    sim.step();
    const Energy e = sim.energy();
    worst = std::max(worst, std::abs(e.balance));
    scale = std::max({scale, e.kinetic + e.strain, std::abs(e.reaction_work)});
    EXPECT_GE(e.inelastic_dissipation, last_d - 1e-12 * scale);
    last_d = e.inelastic_dissipation;
  }
  EXPECT_GT(last_d, 1e-3 * scale);
  EXPECT_LT(worst, 1e-3 * scale) << "dissipated " << last_d << " J of " << scale << " J";
}

} // namespace
} // namespace lamina::membrane
