// Integer keys and scheme keys of a case file (and of --set): an integer is
// read as 64 bits and refused when it does not fit its key's range (never
// wrapped to 32 bits: 4294967297 is not 1), and a key that only the other
// time-integration scheme reads is refused naming the key and the scheme.
#include "restart_helpers.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace lamina::membrane;

namespace {

/// A Newmark square that builds, and its explicit twin.
const std::string kNewmark = test::isotropicSquare(4) +
                             "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n[[fixed]]\nnodes = \"edges\"\n";
const std::string kExplicit = test::isotropicSquare(4) +
                              "[time]\nintegrator = \"explicit\"\nt_end = 1.0e-4\n"
                              "[[fixed]]\nnodes = \"edges\"\n";

/// The error of building case @p text with the --set @p overrides ("" if it builds).
std::string errorWith(const std::string& text, const std::vector<std::string>& overrides) {
  try {
    toml::table doc = lamina::core::parseTomlString(text, "keys.toml");
    for (const auto& o : overrides)
      lamina::core::applyOverride(doc, o);
    buildModel(doc, test::sourcePath("cases/membrane/keys.toml"), test::testSources());
  } catch (const lamina::Error& e) {
    return e.what();
  }
  return "";
}

/// Expects error @p e to name where the value came from (the file, or the
/// --set that gave it) and each of @p parts.
void expectNames(const std::string& e, const std::vector<std::string>& parts) {
  ASSERT_FALSE(e.empty()) << "accepted";
  EXPECT_TRUE(e.find("keys.toml") != std::string::npos || e.rfind("--set ", 0) == 0) << e;
  for (const auto& p : parts)
    EXPECT_NE(e.find(p), std::string::npos) << "no '" << p << "' in: " << e;
}

} // namespace

TEST(MalformedCaseKeys, GoodCasesBuild) {
  EXPECT_EQ(errorWith(kNewmark, {"solver.max_iterations=4294967", "output.field_every=7"}), "");
  EXPECT_EQ(errorWith(kExplicit, {"time.safety=0.5", "time.damping=1.0"}), "");
}

// 4294967297 = 2^32 + 1 wrapped to 1 (a false divergence); 4294967306 to 10.
TEST(MalformedCaseKeys, IntegerBeyondItsRangeIsRefusedNotWrapped) {
  const std::vector<std::pair<std::string, std::string>> bad{
      {"solver.max_iterations=4294967297", "solver.max_iterations"},
      {"output.field_every=4294967306", "output.field_every"},
      {"output.energy_every=4294967297", "output.energy_every"},
      {"solver.drag_iterations=9223372036854775807", "solver.drag_iterations"},
      {"solver.projection=4294967296", "solver.projection"},
      {"solver.max_iterations=-4294967295", "solver.max_iterations"},
      {"output.field_every=-1", "output.field_every"},
      {"output.checkpoint_every=-1", "output.checkpoint_every"},
      {"mesh.nx=4294967300", "mesh.nx"}};
  for (const auto& [set, key] : bad) // a bad --set value: the error names the --set
    expectNames(errorWith(kNewmark, {set}), {"--set " + set + ": '" + key + "'", "got"});
  // In the file itself, not only through --set.
  expectNames(errorWith(kNewmark + "[output]\nfield_every = 4294967306\n", {}),
              {"output.field_every", "2147483647", "4294967306"});
}

TEST(MalformedCaseKeys, NewmarkKeysAreRefusedUnderTheExplicitScheme) {
  for (const char* set :
       {"time.hht_alpha=-0.1", "time.beta1=0.6", "time.beta2=0.6", "time.mass=\"lumped\"",
        "solver.type=\"cg\"", "solver.max_iterations=10"}) {
    const std::string key = std::string(set).substr(0, std::string(set).find('='));
    const std::string named = key.rfind("solver", 0) == 0 ? "solver" : key;
    expectNames(errorWith(kExplicit, {set}), {named, "Newmark scheme only", "explicit"});
  }
}

TEST(MalformedCaseKeys, ExplicitKeysAreRefusedUnderNewmark) {
  for (const char* set : {"time.safety=0.5", "time.damping=1.0"}) {
    const std::string key = std::string(set).substr(0, std::string(set).find('='));
    expectNames(errorWith(kNewmark, {set}), {key, "explicit scheme only", "newmark"});
  }
}

// mesh.renumber takes "rcm" or "none", and only on a gmsh mesh (the
// rectangle is numbered for locality by construction).
TEST(MalformedCaseKeys, RenumberTakesItsChoicesOnGmshMeshesOnly) {
  expectNames(errorWith(kNewmark, {"mesh.type=\"gmsh\"", "mesh.file=\"../meshes/square.geo\"",
                                   "mesh.renumber=\"metis\""}),
              {"mesh.renumber", "metis", "rcm", "none"});
  expectNames(errorWith(kNewmark, {"mesh.renumber=\"none\""}), {"mesh.renumber"});
}

// Through the program: exit 1, the key named, nothing run.
TEST(MalformedCaseKeys, ProgramRefusesWrappedIntegerAndOtherSchemeKey) {
  const test::Folder dir("case-keys");
  const std::string c3 = test::sourcePath("cases/membrane/case3.toml").string();
  for (const auto& [set, key] : std::vector<std::pair<std::string, std::string>>{
           {"solver.max_iterations=4294967297", "solver.max_iterations"},
           {"time.safety=0.5", "time.safety"}}) {
    const auto out = dir.path / "run";
    const auto r =
        lamina::test::run(test::membraneCommand({"run", c3, "--out", out.string(), "--set", set}));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(key), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out / "summary.json")) << set;
  }
}

// --stop-at-step beyond the run's steps (also 2^64 + 1, which the parser
// saturates), or not after a restart's checkpoint, never stops the run: refused.
TEST(MalformedCaseKeys, StopAtStepOutsideTheRunIsRefused) {
  const test::Folder dir("stop-at-step");
  const std::string c3 = test::sourcePath("cases/membrane/case3.toml").string();
  const std::string out = (dir.path / "run").string();
  for (const char* stop : {"61", "18446744073709551617"}) {
    const auto r =
        lamina::test::run(test::membraneCommand({"run", c3, "--out", out, "--stop-at-step", stop}));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("--stop-at-step"), std::string::npos) << r.output;
  }
  auto r =
      lamina::test::run(test::membraneCommand({"run", c3, "--out", out, "--stop-at-step", "10"}));
  ASSERT_EQ(r.code, 0) << r.output;
  r = lamina::test::run(
      test::membraneCommand({"run", c3, "--restart", out, "--stop-at-step", "10"}));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("steps 11 to 60"), std::string::npos) << r.output;
}
