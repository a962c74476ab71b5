/// @file bad_input_test.cpp
/// @brief The table of bad inputs a user meets first, run through the programs.
///
/// Each row: the program exits non-zero, its stderr names the cause (file,
/// key or material), and the library file is byte-identical afterwards. The
/// expected substrings are the user's own input (file names, keys, material
/// names), not text copied from the code under test.

#include "program.hpp"

#include <gtest/gtest.h>

using namespace lamina::test;

namespace {

/// A fresh folder with a valid library holding one catalog entry.
class BadInput : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lamina_bad_input_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    library_ = dir_ / "library.toml";
    ASSERT_EQ(run(materials() + " add vinyl --from-catalog vinyl-fabric").code, 0);
    before_ = slurp(library_);
  }
  void TearDown() override {
    EXPECT_EQ(slurp(library_), before_) << "the library changed";
    fs::remove_all(dir_);
  }
  std::string materials() const {
    return (kBin / "materials").string() + " --library '" + library_.string() + "'";
  }
  /// A small valid membrane case using the library's `vinyl`, with @p edit
  /// applied as extra text appended or replacing a line.
  fs::path
  membraneCase(const std::string& sectionAndTime,
               const std::string& mesh = "[mesh]\ntype = \"rectangle\"\nLx = 1.0\nnx = 4\n") {
    const fs::path p = dir_ / "case.toml";
    write(p, "name = \"bad\"\n" + mesh + sectionAndTime + "\n[[fixed]]\nnodes = \"edges\"\n");
    return p;
  }
  Result membrane(const fs::path& casePath) {
    return run((kBin / "membrane").string() + " run '" + casePath.string() + "' --library '" +
               library_.string() + "' --out '" + (dir_ / "out").string() + "'");
  }
  fs::path dir_, library_;
  std::string before_;
};

const std::string kGoodSection = "[[section]]\nmaterial = \"vinyl\"\nthickness = 6.0e-4\n";
const std::string kGoodTime = "[time]\ndt = 1.0e-4\nt_end = 1.0e-3\n";

} // namespace

TEST_F(BadInput, MalformedTomlNamesFileAndLine) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  const fs::path p = dir_ / "case.toml";
  write(p, "name = \"bad\"\n[mesh\ntype = \"rectangle\"\n");
  const Result r = membrane(p);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find(p.string() + ":2"), std::string::npos) << r.output;
}

TEST_F(BadInput, WrongTypeNamesKey) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  const Result r = membrane(membraneCase(kGoodSection + "[time]\ndt = \"fast\"\nt_end = 1.0e-3\n"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("time.dt"), std::string::npos) << r.output;
}

TEST_F(BadInput, NegativeThicknessNamesKey) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  const Result r = membrane(
      membraneCase("[[section]]\nmaterial = \"vinyl\"\nthickness = -6.0e-4\n" + kGoodTime));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("thickness"), std::string::npos) << r.output;
}

TEST_F(BadInput, NonPositiveTimeStepNamesKey) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  for (const std::string dt : {"0.0", "-1.0e-6"}) {
    const Result r =
        membrane(membraneCase(kGoodSection + "[time]\ndt = " + dt + "\nt_end = 1.0e-3\n"));
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.output.find("time.dt"), std::string::npos) << r.output;
  }
}

TEST_F(BadInput, UnknownKeyNamesKeyAndFile) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  const fs::path p = membraneCase(kGoodSection + kGoodTime + "dt_typo = 3\n");
  const Result r = membrane(p);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("dt_typo"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(p.string()), std::string::npos) << r.output;
}

TEST_F(BadInput, MissingMeshFileNamesIt) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  const Result r = membrane(membraneCase(kGoodSection + kGoodTime,
                                         "[mesh]\ntype = \"gmsh\"\nfile = \"no-such-mesh.msh\"\n"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("no-such-mesh.msh"), std::string::npos) << r.output;
}

TEST_F(BadInput, MeshWithoutTrianglesNamesIt) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  // A geometry with a curve and no surface: gmsh produces no triangle.
  write(dir_ / "wire.geo", "Point(1) = {0, 0, 0, 0.1};\nPoint(2) = {1, 0, 0, 0.1};\n"
                           "Line(1) = {1, 2};\nPhysical Curve(\"edge\") = {1};\n");
  const Result r = membrane(
      membraneCase(kGoodSection + kGoodTime, "[mesh]\ntype = \"gmsh\"\nfile = \"wire.geo\"\n"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("wire.geo"), std::string::npos) << r.output;
}

TEST_F(BadInput, UnknownMaterialNamesLibraryAndListsEntries) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  const Result r = membrane(
      membraneCase("[[section]]\nmaterial = \"unobtainium\"\nthickness = 1.0e-3\n" + kGoodTime));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("unobtainium"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(library_.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("vinyl"), std::string::npos)
      << "should list what the library holds: " << r.output;
}

TEST_F(BadInput, NotPositiveDefiniteConstantsAreRefused) {
  // An isotropic-looking matrix with nu = 0.6 (lambda/mu from E = 1, nu = 0.6):
  // 3 lambda + 2 mu < 0, so the bulk eigenvalue is negative.
  const double E = 1e9, nu = 0.6;
  const double l = E * nu / ((1 + nu) * (1 - 2 * nu)), m = E / (2 * (1 + nu));
  std::ostringstream c;
  c.precision(17);
  c << l + 2 * m << "," << l << "," << l << ",0,0,0," << l + 2 * m << "," << l << ",0,0,0,"
    << l + 2 * m << ",0,0,0," << m << ",0,0," << m << ",0," << m;
  const Result r = run(materials() + " add soft-bad --constants " + c.str() + " --density 1000");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("soft-bad"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("positive definite"), std::string::npos) << r.output;
}

TEST_F(BadInput, TruncatedLibraryIsRefusedAndKeptAsIs) {
  // Cut the library in the middle of its C matrix: every program refuses it,
  // names the file, and nothing rewrites it (TearDown compares bytes).
  const std::string text = slurp(library_);
  write(library_, text.substr(0, text.find("C = [") + 12));
  before_ = slurp(library_);
  for (const std::string& cmd :
       {materials() + " list", materials() + " add more --from-catalog e-glass",
        materials() + " show vinyl"}) {
    const Result r = run(cmd);
    EXPECT_NE(r.code, 0) << cmd;
    EXPECT_NE(r.output.find(library_.string()), std::string::npos) << cmd << ": " << r.output;
  }
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  const Result r = membrane(membraneCase(kGoodSection + kGoodTime));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find(library_.string()), std::string::npos) << r.output;
}

TEST_F(BadInput, CellWithUnknownKeyNamesKey) {
  ASSERT_TRUE(have("homogenize")) << "homogenize was not built";
  const fs::path cell = dir_ / "cell.toml";
  write(cell, "[cell]\nresolution = 8\ncolour = \"red\"\n\n[[phases]]\nname = \"m\"\n"
              "catalog = \"polyurea-hard\"\n");
  const Result r = run((kBin / "homogenize").string() + " '" + cell.string() +
                       "' --name x --library '" + library_.string() + "'");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("colour"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(cell.string()), std::string::npos) << r.output;
}

TEST_F(BadInput, DivergingRunStopsWithTimeAndExitCode3) {
  ASSERT_TRUE(have("membrane")) << "membrane was not built";
  // beta2 = 0, beta1 = 1/2 is the explicit central-difference scheme, stable
  // only for dt < h_el / c_P = 0.25 m / ~77 m/s ~ 3e-3 s for the vinyl (E = 5 MPa,
  // rho = 1133): at dt = 1 s the amplitude grows geometrically and overflows.
  const fs::path p =
      membraneCase(kGoodSection + "[time]\ndt = 1.0\nt_end = 5000.0\nbeta1 = 0.5\nbeta2 = 0.0\n" +
                   "\n[[strike]]\nat = [0.5, 0.5]\nspeed = 1.0\n");
  const Result r = membrane(p);
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("t ="), std::string::npos) << "should say when: " << r.output;
  EXPECT_NE(r.output.find("node"), std::string::npos) << "should say where: " << r.output;
  // The last good state is on disk: the summary and the field series exist.
  EXPECT_TRUE(fs::exists(dir_ / "out" / "summary.json"));
}
