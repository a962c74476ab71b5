// Hostile case files and runs: coordinates that are not finite
// or off the mesh, runs of zero or of astronomically many steps, meshes
// and convergence studies that cannot fit, case names that would escape
// the output folder, divergence at the very first step. Each gives an error
// naming the file and the key (or a complete output folder), never a crash,
// a hang or a silently empty run.
#include "helpers.hpp"
#include "membrane/converge.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace lamina::membrane;

namespace {

/// A struck square like cases/membrane/case3.toml with @p extra appended.
std::string strikeCase(const std::string& time = "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n") {
  return test::isotropicSquare(4) + time + "[[fixed]]\nnodes = \"edges\"\n";
}

std::string errorOf(const std::string& text) {
  return test::buildError(text, "bad.toml");
}

/// Expects building @p text to fail with a message holding every one of @p parts.
void expectRefused(const std::string& text, const std::vector<std::string>& parts) {
  const std::string e = errorOf(text);
  ASSERT_FALSE(e.empty()) << "accepted:\n" << text;
  EXPECT_NE(e.find("bad.toml"), std::string::npos) << e;
  for (const auto& p : parts)
    EXPECT_NE(e.find(p), std::string::npos) << "no '" << p << "' in: " << e;
}

} // namespace

// The reproducers: a strike at [nan, 0.5] indexed node -1, a probe at
// [1e200, 0] read garbage and the run exited 0.
TEST(MalformedRun, NonFiniteAndOffMeshCoordinatesAreRefused) {
  const std::string strike = "[[strike]]\nspeed = 1.0\nat = ";
  expectRefused(strikeCase() + strike + "[nan, 0.5]\n", {"strike[0].at", "finite"});
  expectRefused(strikeCase() + "[[probe]]\nname = \"p\"\nat = [1e200, 0.0]\n",
                {"probe[0].at", "outside mesh"});
  expectRefused(strikeCase() + "[[probe]]\nname = \"p\"\nat = [inf, 0.0]\n", {"probe[0].at"});
  expectRefused(strikeCase() + strike + "[1.5, 0.5]\n", {"strike[0].at", "outside mesh"});
  // On the boundary is on the mesh.
  EXPECT_EQ(errorOf(strikeCase() + "[[probe]]\nname = \"p\"\nat = [1.0, 0.5]\n"), "");
}

// Runs of zero steps reported success; a run of 1e296 steps would never end.
TEST(MalformedRun, ZeroAndEndlessRunsAreRefused) {
  expectRefused(strikeCase("[time]\ndt = 1.0e-5\nt_end = inf\n"), {"time.t_end", "finite"});
  expectRefused(strikeCase("[time]\ndt = 1.0e-300\nt_end = 1.0e-4\n"), {"time.dt", "steps"});
  expectRefused(strikeCase("[time]\ndt = 1.0e-5\nt_end = 1.0e-6\n"), {"time.t_end", "no step"});
  expectRefused(strikeCase("[time]\ndt = nan\nt_end = 1.0e-4\n"), {"time.dt", "finite"});
}

// E = inf was "Young's modulus must be positive, got inf" without file or
// key; NaN input was reported as a divergence.
TEST(MalformedRun, NonFiniteMaterialInputNamesTheKey) {
  std::string text = strikeCase();
  expectRefused(text.replace(text.find("E = 1.0e9"), 9, "E = inf"), {"section[0].E", "finite"});
  text = strikeCase() + "[[strike]]\nat = [0.5, 0.5]\nspeed = nan\n";
  expectRefused(text, {"strike[0].speed", "finite"});
}

// A mesh that cannot fit is refused up front with the amount it needs (was
// a bare std::bad_alloc after minutes).
TEST(MalformedRun, OversizedMeshIsRefusedWithTheMemoryItNeeds) {
  std::string text = strikeCase();
  text.replace(text.find("nx = 4"), 6, "nx = 100000");
  expectRefused(text, {"mesh.nx", "nodes"});
  text = strikeCase();
  text.replace(text.find("nx = 4"), 6, "nx = 14000"); // 2e8 nodes: ~1 TB
  expectRefused(text, {"mesh.nx", "needs about"});
}

// A .geo whose lc asks for ~10^11 triangles is refused after meshing its
// curves, in seconds (it hung in gmsh before).
TEST(MalformedRun, TinyLcGeoIsRefusedNotMeshed) {
  const auto geo = test::tempPath("tiny-lc.geo");
  std::ofstream(geo) << "lc = 1e-6;\nPoint(1) = {0, 0, 0, lc};\nPoint(2) = {0.1, 0, 0, lc};\n"
                        "Point(3) = {0.1, 0.1, 0, lc};\nPoint(4) = {0, 0.1, 0, lc};\n"
                        "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\n"
                        "Line(4) = {4, 1};\nCurve Loop(1) = {1, 2, 3, 4};\n"
                        "Plane Surface(1) = {1};\n";
  const std::string e =
      errorOf("[mesh]\ntype = \"gmsh\"\nfile = \"" + geo.string() +
              "\"\n[[section]]\nE = 1.0e9\nnu = 0.3\ndensity = 1000.0\nthickness = 1.0e-3\n"
              "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n");
  std::filesystem::remove(geo);
  EXPECT_NE(e.find(geo.string()), std::string::npos) << e;
  EXPECT_NE(e.find("nodes"), std::string::npos) << e;
}

// `converge --levels 40` ran 2^39-fold grids; the finest grid is checked
// before the first level runs.
TEST(MalformedRun, ConvergenceLevelsBeyondWhatFitsAreRefusedUpFront) {
  const auto path = test::tempPath("levels.toml");
  std::ofstream(path) << strikeCase();
  for (int levels : {40, 14, 12}) {
    std::string e;
    try {
      runConvergence(path, {}, test::testSources(), levels, 1, true);
    } catch (const lamina::Error& err) {
      e = err.what();
    }
    EXPECT_NE(e.find("levels"), std::string::npos) << levels << ": " << e;
  }
  std::filesystem::remove(path);
}

// Case, probe and constraint names become file names and CSV columns.
TEST(MalformedRun, NamesThatEscapeOrBreakOutputsAreRefused) {
  expectRefused("name = \"../escaped\"\n" + strikeCase(), {"'name'", "case name"});
  expectRefused("name = \"/abs\"\n" + strikeCase(), {"'name'"});
  expectRefused("name = 'a\"<b'\n" + strikeCase(), {"'name'"});
  expectRefused(strikeCase() + "[[probe]]\nname = \"p,q\"\nat = [0.5, 0.5]\n", {"probe[0].name"});
  expectRefused(strikeCase() + "[[strike]]\nname = \"s\\n\"\nat = [0.5, 0.5]\nspeed = 1.0\n",
                {"strike[0].name"});
}

// Divergence at the first step (a strike at 1e300 m/s: the kinetic energy
// overflows at t = 0) exits with DivergenceError but leaves a complete
// folder: summary.json naming the divergence and CSVs renamed into place.
TEST(MalformedRun, DivergenceAtTheFirstStepWritesTheSummary) {
  const Model model =
      test::modelFromText(strikeCase() + "[[strike]]\nat = [0.5, 0.5]\nspeed = 1e300\n"
                                         "[[probe]]\nname = \"c\"\nat = [0.5, 0.5]\n");
  const auto out = test::tempPath("diverge-out");
  std::filesystem::remove_all(out);
  RunOptions opt;
  opt.out_dir = out;
  opt.quiet = true;
  EXPECT_THROW(runModel(model, opt), lamina::DivergenceError);
  ASSERT_TRUE(std::filesystem::exists(out / "summary.json"));
  std::ifstream in(out / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_TRUE(summary.contains("diverged")) << summary.dump();
  for (const auto& f : std::filesystem::directory_iterator(out))
    EXPECT_NE(f.path().extension(), ".part") << f.path();
  EXPECT_TRUE(std::filesystem::exists(out / "probes.csv"));
  std::filesystem::remove_all(out);
}
