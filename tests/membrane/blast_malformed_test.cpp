// Bad blast input gives an error that names the value and the cause.
#include "membrane/loads/blast.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

using namespace lamina::membrane;

namespace {
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const lamina::Error& e) {
    return e.what();
  }
  return "";
}

std::string csvError(const std::string& name, const std::string& content) {
  const auto p = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + name);
  std::ofstream(p) << content;
  const std::string e = errorOf([&] { PressureTable::readCsv(p.string()); });
  std::filesystem::remove(p);
  return e;
}

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}
} // namespace

TEST(BlastMalformed, ScaledDistanceOutsideTheFitsIsRefusedWithItsValue) {
  // 1 kg at 0.1 m: Z = 0.1 < 0.2 (hemispherical lower end).
  const auto e = errorOf([] { kingeryBulmash(1.0, 0.1, Burst::Hemispherical); });
  EXPECT_TRUE(has(e, "Z = 0.1 m/kg^(1/3)")) << e;
  EXPECT_TRUE(has(e, "[0.2, 40]")) << e;
  const auto far = errorOf([] { kingeryBulmash(1.0, 50.0, Burst::Spherical); });
  EXPECT_TRUE(has(far, "Z = 50")) << far;
  EXPECT_TRUE(has(far, "spherical")) << far;
}

TEST(BlastMalformed, ClampPolicyEvaluatesAtTheEndAndSaysSo) {
  const BlastParameters c = kingeryBulmash(1.0, 0.1, Burst::Hemispherical, OutOfRange::Clamp);
  const BlastParameters end = kingeryBulmash(1.0, 0.2, Burst::Hemispherical);
  EXPECT_TRUE(c.clamped);
  EXPECT_FALSE(end.clamped);
  EXPECT_DOUBLE_EQ(c.incident_pressure, end.incident_pressure);
  EXPECT_DOUBLE_EQ(c.scaled_distance, 0.1); // the true value is kept
}

TEST(BlastMalformed, NonPositiveChargeDistanceOrFactor) {
  EXPECT_TRUE(has(errorOf([] { kingeryBulmash(0.0, 3.0, Burst::Spherical); }), "charge"));
  EXPECT_TRUE(has(errorOf([] { kingeryBulmash(1.0, -3.0, Burst::Spherical); }), "distance"));
  EXPECT_TRUE(has(errorOf([] { kingeryBulmash(1.0, NAN, Burst::Spherical); }), "distance"));
  BlastCharge c;
  c.mass = 1.0;
  c.tnt_equivalence = 0.0;
  EXPECT_TRUE(has(errorOf([&] { c.parametersAt(Eigen::Vector3d(0, 0, 3)); }), "TNT-equivalence"));
  EXPECT_TRUE(has(errorOf([] {
                    parseBurst("airburst", {"case.toml", 4, "blast.burst"});
                  }),
                  "case.toml:4"));
  EXPECT_TRUE(has(errorOf([] { friedlanderDecay(1.0, 0.0, 1.0); }), "duration"));
}

TEST(BlastMalformed, PressureCsvErrorsNameFileAndLine) {
  const auto text = csvError("-bad-row.csv", "time,pressure\n0,0\n1e-3,abc\n");
  EXPECT_TRUE(has(text, "-bad-row.csv:3")) << text;
  const auto order = csvError("-order.csv", "0,0\n2e-3,5\n1e-3,0\n");
  EXPECT_TRUE(has(order, "increase strictly")) << order;
  EXPECT_TRUE(has(order, "row 3")) << order;
  const auto one = csvError("-one.csv", "0,0\n");
  EXPECT_TRUE(has(one, "at least two")) << one;
  const auto missing = errorOf([] { PressureTable::readCsv("/nonexistent/p.csv"); });
  EXPECT_TRUE(has(missing, "/nonexistent/p.csv")) << missing;
}
