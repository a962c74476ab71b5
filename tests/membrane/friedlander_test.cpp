// The Friedlander pulse carries the impulse it was built for, the
// angle-of-incidence combination has the limits of its source, and a user
// pressure table integrates exactly.
#include "membrane/loads/blast.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

using namespace lamina::membrane;

namespace {
/// Composite Simpson rule of the pulse over [0, td] with n (even) intervals.
double simpson(const FriedlanderPulse& f, int n) {
  const double h = f.duration / n;
  double s = f.pressure(0) + f.pressure(f.duration);
  for (int i = 1; i < n; ++i)
    s += (i % 2 ? 4.0 : 2.0) * f.pressure(i * h);
  return s * h / 3.0;
}
} // namespace

// Closed form: int_0^1 (1 - x) e^(-b x) dx = (b - 1 + e^-b) / b^2; at b = 0 a
// triangle (1/2); checked against Simpson quadrature, whose error for 2000
// intervals of a smooth integrand with |f''''| <= b^4 is below 1e-10 here.
TEST(Friedlander, ImpulseFractionMatchesQuadrature) {
  EXPECT_DOUBLE_EQ(friedlanderImpulseFraction(0.0), 0.5);
  for (const double b : {-2.0, -1e-5, 1e-5, 0.3, 1.0, 4.0, 12.0}) {
    const FriedlanderPulse f{1.0, 1.0, b};
    EXPECT_NEAR(friedlanderImpulseFraction(b), simpson(f, 2000), 1e-10) << "b = " << b;
  }
}

// The solved decay reproduces the Kingery-Bulmash impulse: the pulse built
// from (P, td, I) integrates to I (Simpson with 20000 intervals: the
// integrand's scale is td/b with b < 40, relative error < 1e-9).
TEST(Friedlander, PulseIntegratesToTheFittedImpulse) {
  for (const Burst burst : {Burst::Hemispherical, Burst::Spherical}) {
    for (const double z : {0.3, 0.8, 1.5, 3.0, 8.0, 20.0, 39.0}) {
      const BlastParameters p = kingeryBulmash(50.0, z * std::cbrt(50.0), burst);
      const BlastHistory h = blastHistory(p);
      EXPECT_NEAR(simpson(h.incident, 20000) / p.incident_impulse, 1.0, 1e-9)
          << burstName(burst) << " Z = " << z;
      EXPECT_NEAR(simpson(h.reflected, 20000) / p.reflected_impulse, 1.0, 1e-9)
          << burstName(burst) << " Z = " << z;
      EXPECT_DOUBLE_EQ(h.incident.pressure(0.0), p.incident_pressure);
      EXPECT_EQ(h.incident.pressure(p.positive_duration * 1.0001), 0.0);
      // Before arrival nothing; at arrival the full peak on a face-on surface.
      EXPECT_EQ(h.pressure(p.arrival_time * 0.999, 1.0), 0.0);
      EXPECT_DOUBLE_EQ(h.pressure(p.arrival_time, 1.0), p.reflected_pressure);
    }
  }
}

// Randers-Pehrson & Bannister (1997): face-on (cos a = 1) gives the reflected
// pressure, edge-on (cos a = 0) and faces turned away give the incident one;
// in between the weights cos^2 a and (1 - cos a)^2 are exact arithmetic.
TEST(Friedlander, AngleOfIncidenceCombination) {
  EXPECT_DOUBLE_EQ(combineIncidentReflected(10.0, 70.0, 1.0), 70.0);
  EXPECT_DOUBLE_EQ(combineIncidentReflected(10.0, 70.0, 0.0), 10.0);
  EXPECT_DOUBLE_EQ(combineIncidentReflected(10.0, 70.0, -0.4), 10.0);
  EXPECT_DOUBLE_EQ(combineIncidentReflected(10.0, 70.0, 0.5), 70.0 * 0.25 + 10.0 * 0.25);
}

// A triangular history: p rises linearly to 2e5 Pa in 1 ms and falls to 0 at
// 3 ms; area = 0.5 * 2e5 * 3e-3 = 300 Pa s; read from CSV with a header and a
// comment; p(0.5 ms) = 1e5 Pa; zero outside the table.
TEST(PressureTable, CsvTriangleImpulseAndInterpolation) {
  const auto path =
      std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "-triangle.csv");
  std::ofstream(path) << "time,pressure\n# a triangle\n0,0\n1e-3,2e5\n3e-3,0\n";
  const PressureTable t = PressureTable::readCsv(path.string());
  std::filesystem::remove(path);
  EXPECT_NEAR(t.impulse(), 300.0, 1e-9);
  EXPECT_NEAR(t.pressure(0.5e-3), 1e5, 1e-6);
  EXPECT_NEAR(t.pressure(2e-3), 1e5, 1e-6);
  EXPECT_EQ(t.pressure(-1e-3), 0.0);
  EXPECT_EQ(t.pressure(4e-3), 0.0);
}
