// The blast as a follower pressure (BlastPressure on ElementPressure): a small flat panel facing
// the charge receives the normally reflected impulse times its area, one seen edge-on only the
// incident impulse times its area, and the load follows the panel when it
// turns. A user pressure table gives its impulse times the area. Over time
// steps (the means SecondOrderSystem::external gives each step), the steps together receive the
// impulse whatever the step, also one longer than the whole pulse.
#include "membrane/loads/blast_pressure.hpp"
#include "membrane/model/mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace lamina::membrane;

namespace {

/// A square panel of side @p s centred at @p c in the plane spanned by the
/// unit vectors @p e1, @p e2 (normal e1 x e2 by the node order), n x n squares.
struct Panel {
  Mesh mesh;
  std::vector<int> elements;
  double area = 0;
};

Panel panel(const Eigen::Vector3d& c, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
            double s, int n) {
  Panel p;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector3d x = c + s * ((i / double(n) - 0.5) * e1 + (j / double(n) - 0.5) * e2);
      p.mesh.nodes.emplace_back(x.x(), x.y());
      p.mesh.z.push_back(x.z());
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, d = a + n + 1, e = d + 1;
      p.mesh.triangles.push_back({a, b, e});
      p.mesh.triangles.push_back({a, e, d});
    }
  p.mesh.region_of.assign(p.mesh.triangles.size(), 0);
  p.mesh.regions = {"all"};
  p.mesh.source = "panel";
  for (int e = 0; e < p.mesh.numElements(); ++e)
    p.elements.push_back(e);
  p.area = s * s;
  return p;
}

/// int F dt over [t0, t1] (trapezoids, @p steps intervals) of the total force.
Eigen::Vector3d forceImpulse(const BlastPressure& load, const Panel& p, const Eigen::VectorXd& u,
                             double t0, double t1, int steps) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const double dt = (t1 - t0) / steps;
  for (int k = 0; k <= steps; ++k) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
    load.add(t0 + k * dt, p.mesh, u, Eigen::VectorXd(), f);
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < f.size(); i += 3)
      total += f.segment<3>(i);
    sum += (k == 0 || k == steps ? 0.5 : 1.0) * dt * total;
  }
  return sum;
}

BlastCharge tenKg() {
  BlastCharge c;
  c.mass = 10.0; // Z = 5 / 10^(1/3) = 2.32 m/kg^(1/3) at 5 m
  c.burst = Burst::Hemispherical;
  return c;
}

// Tolerance 0.3 %: over the 0.2 m panel at 5 m the distance and the angle to
// the charge vary by (0.1 / 5)^2 ~ 4e-4 (the impulse with them); the
// trapezoid rule over 20000 steps misses at most P dt / 2 per jump at the
// arrival, ~4e-4 of the impulse.
constexpr double kTol = 3e-3;

} // namespace

TEST(BlastPressure, FaceOnPanelReceivesReflectedImpulseTimesArea) {
  const BlastCharge charge = tenKg();
  const Panel p = panel({0, 0, 5.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.2, 4);
  const BlastPressure load("blast", p.elements, p.mesh, charge, Geometry::Current);
  const BlastParameters bp = kingeryBulmash(10.0, 5.0, Burst::Hemispherical);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * p.mesh.numNodes());
  const Eigen::Vector3d J =
      forceImpulse(load, p, u, load.firstArrival() - 1e-5, load.lastEnd() + 1e-5, 20000);
  EXPECT_NEAR(J.z() / (bp.reflected_impulse * p.area), 1.0, kTol); // away from the charge: +z
  EXPECT_NEAR(J.x(), 0.0, 1e-9 * std::abs(J.z()));
  EXPECT_NEAR(J.y(), 0.0, 1e-9 * std::abs(J.z()));
}

TEST(BlastPressure, EdgeOnPanelReceivesIncidentImpulseOnly) {
  const BlastCharge charge = tenKg();
  // Plane x = 0, containing the direction to the charge: cos a = 0.
  const Panel p = panel({0, 0, 5.0}, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), 0.2, 4);
  const BlastPressure load("blast", p.elements, p.mesh, charge, Geometry::Current);
  const BlastParameters bp = kingeryBulmash(10.0, 5.0, Burst::Hemispherical);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * p.mesh.numNodes());
  const Eigen::Vector3d J =
      forceImpulse(load, p, u, load.firstArrival() - 1e-5, load.lastEnd() + 1e-5, 20000);
  EXPECT_NEAR(std::abs(J.x()) / (bp.incident_impulse * p.area), 1.0, kTol);
  EXPECT_NEAR(J.z(), 0.0, 1e-9 * std::abs(J.x())); // normal to the panel only
}

// The load follows the surface: the face-on panel turned by 90 degrees about
// its own centre line (through u, the reference stays face-on) is edge-on
// and receives the incident impulse along its new normal.
TEST(BlastPressure, LoadFollowsTheTurnedPanel) {
  const BlastCharge charge = tenKg();
  const Panel p = panel({0, 0, 5.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.2, 4);
  const BlastPressure load("blast", p.elements, p.mesh, charge, Geometry::Current);
  Eigen::VectorXd u(3 * p.mesh.numNodes());
  for (int i = 0; i < p.mesh.numNodes(); ++i) { // x -> z about the line x = 0, z = 5
    const Eigen::Vector3d r = p.mesh.point(i) - Eigen::Vector3d(0, 0, 5.0);
    const Eigen::Vector3d turned(0.0, r.y(), 5.0 + r.x());
    u.segment<3>(3 * i) = turned - p.mesh.point(i);
  }
  const BlastParameters bp = kingeryBulmash(10.0, 5.0, Burst::Hemispherical);
  const Eigen::Vector3d J =
      forceImpulse(load, p, u, load.firstArrival() - 1e-5, load.lastEnd() + 1e-5, 20000);
  EXPECT_NEAR(std::abs(J.x()) / (bp.incident_impulse * p.area), 1.0, kTol);
  EXPECT_NEAR(J.z(), 0.0, 1e-9 * std::abs(J.x()));
}

// A pressure table on a panel: the force integral equals the table's impulse
// times the area along +n (trapezoids on the table's own breakpoints are
// exact for the piecewise-linear history: relative 1e-12).
TEST(BlastPressure, PressureTableGivesItsImpulseTimesArea) {
  const Panel p = panel({1, 2, 3}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.5, 3);
  const PressureTable table({0.0, 1e-3, 3e-3}, {0.0, 2e5, 0.0});
  const BlastPressure load("table", p.elements, table, Geometry::Current);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * p.mesh.numNodes());
  const Eigen::Vector3d J = forceImpulse(load, p, u, 0.0, 3e-3, 3000);
  EXPECT_NEAR(J.z() / (table.impulse() * p.area), 1.0, 1e-12);
}

namespace {
/// The impulse a scheme of step @p dt delivers from @p load (starting at
/// t = 0, up to @p t_end): sum over the steps of the total force at t_n
/// times the time it acts for, dt (dt / 2 at t = 0), the force being the
/// mean over [t_n - dt/2, t_n + dt/2] as SecondOrderSystem::external gives it (@p mean), or the
/// value at t_n (a sample, what the schemes used before).
Eigen::Vector3d stepImpulse(const BlastPressure& load, const Panel& p, double dt, double t_end,
                            bool mean) {
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * p.mesh.numNodes());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (long n = 0; static_cast<double>(n) * dt <= t_end; ++n) {
    const double t = static_cast<double>(n) * dt;
    const LoadTime when = mean ? LoadTime(t, std::max(0.0, t - dt / 2), t + dt / 2) : LoadTime(t);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
    load.add(when, p.mesh, u, Eigen::VectorXd(), f);
    for (Eigen::Index i = 0; i < f.size(); i += 3)
      sum += (n == 0 ? dt / 2 : dt) * f.segment<3>(i);
  }
  return sum;
}
} // namespace

// Whatever the step, from a tenth of the positive phase to seven times it
// and whatever the phase of the arrival in it, the steps together receive
// the Kingery-Bulmash reflected impulse times the area (the face-on panel,
// kTol: the spread over the panel). Sampled at t_n instead, a step longer
// than the pulse receives nothing.
TEST(BlastPressure, StepsReceiveTheImpulseWhateverTheStep) {
  const BlastCharge charge = tenKg();
  const Panel p = panel({0, 0, 5.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.2, 4);
  const BlastPressure load("blast", p.elements, p.mesh, charge, Geometry::Current);
  const BlastParameters bp = kingeryBulmash(10.0, 5.0, Burst::Hemispherical);
  const double td = bp.positive_duration, end = load.lastEnd() + 10 * td;
  for (const double ratio : {0.1, 0.37, 1.0, 1.3, 7.0, 7.31, 7.77, 23.0}) {
    const Eigen::Vector3d J = stepImpulse(load, p, ratio * td, end + 25 * td, true);
    EXPECT_NEAR(J.z() / (bp.reflected_impulse * p.area), 1.0, kTol) << "dt = " << ratio << " td";
  }
  // A step ending where the pulse ends: the samples at t_0 = 0 and t_1 see
  // no pressure, the means the whole impulse.
  const double dt = load.lastEnd();
  EXPECT_EQ(stepImpulse(load, p, dt, 3 * dt, false).z(), 0.0);
  EXPECT_NEAR(stepImpulse(load, p, dt, 3 * dt, true).z() / (bp.reflected_impulse * p.area), 1.0,
              kTol);
}

// A pressure table: the steps receive its impulse times the area, exactly
// (piecewise-linear integrals; relative 1e-12), for steps shorter and
// longer than the table, and a step straddling its start or end.
TEST(BlastPressure, TableStepsReceiveItsImpulseWhateverTheStep) {
  const Panel p = panel({1, 2, 3}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.5, 3);
  const PressureTable table({0.4e-3, 1e-3, 1.3e-3, 3e-3}, {5e4, 2e5, -1e4, 3e4});
  const BlastPressure load("table", p.elements, table, Geometry::Current);
  // The same impulse by hand: trapezoids of the rows (the jumps at both
  // ends are part of the history: 0 outside).
  const double impulse =
      0.5 * (5e4 + 2e5) * 0.6e-3 + 0.5 * (2e5 - 1e4) * 0.3e-3 + 0.5 * (-1e4 + 3e4) * 1.7e-3;
  for (const double dt : {1e-5, 2.9e-4, 1e-3, 2.6e-3, 7e-3})
    EXPECT_NEAR(stepImpulse(load, p, dt, 0.02, true).z() / (impulse * p.area), 1.0, 1e-12)
        << "dt = " << dt;
}

// The closed-form integral of the Friedlander pulse over a part of its
// positive phase against Simpson's rule on the pressure (2000 intervals:
// error ~ (h^4) p'''' ~ 1e-13 relative), and over the whole phase against
// impulse(); for decays around the series' switch (|b x| = 0.1) too.
TEST(BlastPressure, FriedlanderIntegralIsExact) {
  for (const double b : {-0.5, 0.0, 1e-7, 0.099, 0.1, 0.101, 0.3, 2.0, 9.0}) {
    const FriedlanderPulse f{1e5, 4e-3, b};
    EXPECT_NEAR(f.impulseBetween(-1.0, 1.0) / f.impulse(), 1.0, 1e-13) << "b = " << b;
    const double a = 0.7e-3, c = 2.9e-3;
    const int n = 2000;
    const double h = (c - a) / n;
    double s = f.pressure(a) + f.pressure(c);
    for (int i = 1; i < n; ++i)
      s += (i % 2 ? 4.0 : 2.0) * f.pressure(a + i * h);
    EXPECT_NEAR(f.impulseBetween(a, c) / (s * h / 3), 1.0, 1e-11) << "b = " << b;
    EXPECT_NEAR((f.impulseBetween(0, a) + f.impulseBetween(a, 1.0)) / f.impulse(), 1.0, 1e-13);
    EXPECT_EQ(f.impulseBetween(-2.0, -1.0), 0.0);
    EXPECT_EQ(f.impulseBetween(5e-3, 1.0), 0.0);
  }
}
