// A blast pulse shorter than the explicit step is not missed: a free, heavy
// sheet (so that it barely moves during the pulse) under a charge overhead
// gains the momentum of the Kingery-Bulmash impulses on its elements,
// whatever the step, from a tenth of the positive phase to several times it;
// a pressure table gives its impulse times the area. And the small stiff
// sheet whose steps jumped over the pulse (max |w| = 0, no external work)
// now moves.
#include "helpers.hpp"

#include "membrane/loads/blast.hpp"
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
    const Model m = test::modelFromText(
        freeSheet(dt, 0.02, "[[blast]]\ntable = \"" + csv.string() + "\"\n"));
    EXPECT_NEAR(momentumAtEnd(m).z() / impulse, 1.0, 1e-4) << "dt = " << dt; // area 1 m^2
  }
}

// The report's case: 2 x 2 elements, E 1e5, prestress 0.1, t_end 0.05 s:
// the stable step (~0.1 s) is far longer than the pulse (~3 ms). Before,
// max |w| = 0 and no external work; now the sheet moves and the blast works.
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
  const auto summary = runModel(m, opt);
  ASSERT_GT(summary["dt"].get<double>(),
            kingeryBulmash(10.0, 5.0, Burst::Hemispherical).positive_duration)
      << "the step no longer exceeds the pulse";
  EXPECT_GT(summary["max_abs_w"].get<double>(), 0.0);
  EXPECT_GT(std::abs(summary["energy"]["external_work"].get<double>()), 0.0);
}
