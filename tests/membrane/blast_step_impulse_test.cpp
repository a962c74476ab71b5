// A blast pulse shorter than the explicit step is not missed: a free, heavy
// sheet (so that it barely moves during the pulse) under a charge overhead
// gains the momentum of the Kingery-Bulmash impulses on its elements,
// whatever the step, from a tenth of the positive phase to several times it;
// a pressure table gives its impulse times the area. And the small stiff
// sheet whose steps jumped over the pulse (max |w| = 0, no external work)
// now moves. The same holds for the time profiles of [[load]] (a pulse
// shorter than a Newmark step).
#include "helpers.hpp"

#include "membrane/loads/blast.hpp"
#include "membrane/model/profile.hpp"
#include "membrane/run.hpp"
#include "restart_helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace lamina::membrane;

namespace {

/// A free 1 m sheet of 2 x 2 squares, 1000 kg/m^2 (density 1e6, 1 mm),
/// E = 1e5 Pa, explicit steps of @p dt to @p t_end, and the blast @p blast.
std::string freeSheet(double dt, double t_end, const std::string& blast) {
  return "model = \"large_deflection\"\n[mesh]\nLx = 1.0\nnx = 2\n[[section]]\nE = 1.0e5\n"
         "nu = 0.3\ndensity = 1.0e6\nthickness = 1.0e-3\n[time]\nintegrator = \"explicit\"\n"
         "dt = " +
         lamina::core::formatExact(dt) + "\nt_end = " + lamina::core::formatExact(t_end) +
         "\n[output]\nfields = false\n" + blast;
}

/// 10 kg TNT, hemispherical, 5 m above the sheet's centre (Z = 2.32).
const std::string kCharge =
    "[[blast]]\ncharge = 10.0\nposition = [0.5, 0.5, 5.0]\nburst = \"hemispherical\"\n";

/// The sheet's momentum (kg m/s, sum of M v) after running @p m to its end.
Eigen::Vector3d momentumAtEnd(const Model& m) {
  Simulation sim(m);
  const long steps = std::lround(std::ceil(m.time.t_end / sim.integrator().timeStep() - 1e-9));
  for (long s = 0; s < steps; ++s)
    sim.step();
  const Eigen::VectorXd p = sim.structure().mass() * sim.v();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < p.size(); i += 3)
    sum += p.segment<3>(i);
  return sum;
}

/// The impulse on the flat sheet by the closed forms: per element, the
/// Kingery-Bulmash impulses at its centroid combined over the angle of
/// incidence (Randers-Pehrson & Bannister, linear in the two pulses), times
/// its area, along -z (away from the charge above).
double expectedImpulse(const Model& m) {
  BlastCharge c;
  c.mass = 10.0;
  c.position = Eigen::Vector3d(0.5, 0.5, 5.0);
  double sum = 0;
  for (const auto& tri : m.mesh.triangles) {
    const Eigen::Vector3d a = m.mesh.point(tri[0]), b = m.mesh.point(tri[1]),
                          d = m.mesh.point(tri[2]);
    const Eigen::Vector3d x = (a + b + d) / 3.0;
    const double area = 0.5 * (b - a).cross(d - a).norm();
    const BlastParameters p = c.parametersAt(x);
    const double cos_a = (c.position - x).normalized().z();
    sum += area * combineIncidentReflected(p.incident_impulse, p.reflected_impulse, cos_a);
  }
  return -sum;
}

} // namespace

// Tolerance 1e-4: the sheet moves ~0.5 m/s, ~2 mm during the pulse, which
// changes the distances to the charge (5 m) and the normals by less than
// 1e-4; the step sums are otherwise exact (closed-form integrals).
TEST(BlastStepImpulse, FreeSheetGainsTheBlastImpulseWhateverTheStep) {
  const Model probe = test::modelFromText(freeSheet(1e-5, 1e-4, kCharge));
  const double expected = expectedImpulse(probe);
  const BlastParameters centre = kingeryBulmash(10.0, 5.0, Burst::Hemispherical);
  const double td = centre.positive_duration, t_end = 4 * (centre.arrival_time + td);
  for (const double ratio : {0.1, 0.77, 1.0, 3.3, 11.0}) {
    const Model m = test::modelFromText(freeSheet(ratio * td, t_end, kCharge));
    const Eigen::Vector3d P = momentumAtEnd(m);
    EXPECT_NEAR(P.z() / expected, 1.0, 1e-4) << "dt = " << ratio << " td";
    EXPECT_NEAR(P.x(), 0.0, 1e-6 * std::abs(expected));
    EXPECT_NEAR(P.y(), 0.0, 1e-6 * std::abs(expected));
  }
}

// A pressure table of 0.2 ms on the sheet, steps of 0.05 to 3 ms: momentum
// = table impulse x area along +n (+z), to 1e-4 (the sheet's motion).
TEST(BlastStepImpulse, FreeSheetGainsTheTableImpulseWhateverTheStep) {
  const test::Folder dir("blast-step-table");
  const auto csv = dir.path / "pulse.csv";
  std::ofstream(csv) << "time,pressure\n1.0e-3,0\n1.1e-3,4.0e4\n1.2e-3,0\n";
  const double impulse = 0.5 * 4e4 * 0.2e-3; // the triangle, Pa s
  for (const double dt : {5e-5, 1e-4, 3e-4, 3e-3}) {
    const Model m =
        test::modelFromText(freeSheet(dt, 0.02, "[[blast]]\ntable = \"" + csv.string() + "\"\n"));
    EXPECT_NEAR(momentumAtEnd(m).z() / impulse, 1.0, 1e-4) << "dt = " << dt; // area 1 m^2
  }
}

// The report's case: 2 x 2 elements, E 1e5, prestress 0.1, t_end 0.05 s:
// the stable step (~0.03 s) is far longer than the pulse (~3 ms). Before,
// max |w| = 0 and no external work, no warning; now the sheet moves, the
// blast works, and a warning says that the pulse's shape is not resolved.
TEST(BlastStepImpulse, SmallStiffSheetIsNotMissed) {
  const Model m = test::modelFromText(
      "model = \"large_deflection\"\n[mesh]\nLx = 1.0\nnx = 2\n[[section]]\nE = 1.0e5\n"
      "nu = 0.3\ndensity = 1000.0\nthickness = 1.0e-3\nprestress = 0.1\n[time]\n"
      "integrator = \"explicit\"\nt_end = 0.05\n[[fixed]]\nnodes = \"edges\"\n[output]\n"
      "fields = false\n" +
      kCharge);
  const test::Folder dir("blast-step-stiff");
  RunOptions opt;
  opt.out_dir = dir.path / "run";
  opt.quiet = true;
  ::testing::internal::CaptureStderr();
  const auto summary = runModel(m, opt);
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("warning: [[blast]] 'blast"), std::string::npos) << said;
  EXPECT_NE(said.find("longer than its positive phase"), std::string::npos) << said;
  ASSERT_GT(summary["dt"].get<double>(),
            kingeryBulmash(10.0, 5.0, Burst::Hemispherical).positive_duration)
      << "the step no longer exceeds the pulse";
  EXPECT_GT(summary["max_abs_w"].get<double>(), 0.0);
  EXPECT_GT(std::abs(summary["energy"]["external_work"].get<double>()), 0.0);
}

// The integral of each time profile (every kind piecewise linear), against
// areas worked out by hand.
TEST(LoadStepImpulse, ProfileIntegralsAreExact) {
  auto profile = [](const std::string& keys) {
    const toml::table doc = lamina::core::parseTomlString(keys, "profile.toml");
    const lamina::core::TableReader r(doc, "profile.toml");
    return TimeProfile::read(r);
  };
  const TimeProfile step = profile("profile = \"step\"\nt0 = 1.0\n");
  EXPECT_DOUBLE_EQ(step.integral(0.0, 3.0), 2.0);
  EXPECT_DOUBLE_EQ(step.integral(1.5, 2.0), 0.5);
  const TimeProfile ramp = profile("profile = \"ramp\"\nt0 = 1.0\nrise = 2.0\n");
  EXPECT_DOUBLE_EQ(ramp.integral(0.0, 4.0), 2.0); // the triangle 1, then 1 x 1
  EXPECT_DOUBLE_EQ(ramp.integral(1.0, 2.0), 0.25);
  const TimeProfile pulse = profile("profile = \"pulse\"\nt0 = 1.0\nduration = 0.5\n");
  EXPECT_DOUBLE_EQ(pulse.integral(0.0, 10.0), 0.5);
  EXPECT_DOUBLE_EQ(pulse.integral(1.25, 3.0), 0.25);
  const TimeProfile table =
      profile("profile = \"table\"\ntable = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0]]\n");
  EXPECT_DOUBLE_EQ(table.integral(-1.0, 4.0), 7.0); // 0, the triangle 1, 2 x 2, then 2 x 1
  EXPECT_DOUBLE_EQ(table.integral(0.5, 1.0), 0.75);
  EXPECT_DOUBLE_EQ(profile("").integral(0.25, 2.0), 1.75); // constant
}

// The class beyond the blast: a pressure pulse ([[load]] profile "pulse")
// shorter than the Newmark step, on a free sheet (1 kg/m^2, E 1e9): the
// sheet gains the pulse's impulse P d A whatever the step (before: the
// samples at t_n missed it, or caught it whole for a step). Tolerance
// 1e-10: with the factorized solve, Newmark's momentum is exact up to
// round-off (the internal forces sum to zero; ~30 steps).
TEST(LoadStepImpulse, NewmarkFreeSheetGainsAPulseShorterThanItsStep) {
  for (const double dt : {1e-4, 3e-4, 1e-3}) {
    const Model m = test::modelFromText(
        test::isotropicSquare(2) + "[time]\ndt = " + lamina::core::formatExact(dt) +
        "\nt_end = 3.0e-3\n[[load]]\ntype = \"pressure\"\nvalue = 100.0\nprofile = \"pulse\"\n"
        "t0 = 1.03e-3\nduration = 5.0e-5\n[solver]\ntype = \"cholesky\"\n[output]\n"
        "fields = false\n");
    EXPECT_NEAR(momentumAtEnd(m).z() / (100.0 * 5e-5), 1.0, 1e-10) << "dt = " << dt;
  }
}
