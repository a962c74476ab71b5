// Malformed case files: each error names the file and the cause.
#include "helpers.hpp"
#include "materials/library.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace lamina::membrane;

namespace {
const std::string kGood = test::isotropicSquare(4) + R"(
[time]
dt = 1.0e-5
t_end = 1.0e-4
)";

/// The error message of building @p text, or "" if it builds.
std::string errorOf(const std::string& text, const std::string& name = "bad.toml") {
  try {
    test::modelFromText(text, name);
  } catch (const lamina::Error& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

std::filesystem::path tempFile(const std::string& name, const std::string& content) {
  const auto p = test::tempPath(name);
  std::ofstream(p) << content;
  return p;
}
} // namespace

TEST(MembraneMalformed, GoodCaseBuilds) {
  EXPECT_EQ(errorOf(kGood), "");
}

TEST(MembraneMalformed, UnknownKeyIsNamedWithFileAndLine) {
  const auto e = errorOf(replaced(kGood, "t_end", "t_ned = 1.0\nt_end"));
  EXPECT_NE(e.find("bad.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("time.t_ned"), std::string::npos) << e;
}

TEST(MembraneMalformed, NonPositiveTimeStepIsRejected) {
  for (const char* dt : {"dt = 0.0", "dt = -1.0e-5"}) {
    const auto e = errorOf(replaced(kGood, "dt = 1.0e-5", dt));
    EXPECT_NE(e.find("time.dt"), std::string::npos) << e;
    EXPECT_NE(e.find("> 0"), std::string::npos) << e;
  }
}

TEST(MembraneMalformed, NegativeThicknessIsRejected) {
  const auto e = errorOf(replaced(kGood, "thickness = 1.0e-3", "thickness = -1.0e-3"));
  EXPECT_NE(e.find("thickness"), std::string::npos) << e;
}

TEST(MembraneMalformed, MissingMeshFileIsNamed) {
  const auto e =
      errorOf(replaced(kGood, "Lx = 1.0\nnx = 4", "type = \"gmsh\"\nfile = \"nowhere.msh\""));
  EXPECT_NE(e.find("nowhere.msh"), std::string::npos) << e;
  EXPECT_NE(e.find("not found"), std::string::npos) << e;
}

TEST(MembraneMalformed, MeshWithoutTrianglesNamesTheFile) {
  const auto geo =
      tempFile("lamina-lines-only.geo", "Point(1) = {0, 0, 0, 0.1};\nPoint(2) = {1, 0, 0, 0.1};\n"
                                        "Line(1) = {1, 2};\n");
  const auto e = errorOf(
      replaced(kGood, "Lx = 1.0\nnx = 4", "type = \"gmsh\"\nfile = \"" + geo.string() + "\""));
  EXPECT_NE(e.find("lamina-lines-only.geo"), std::string::npos) << e;
  EXPECT_NE(e.find("no"), std::string::npos) << e;
  EXPECT_NE(e.find("triangles"), std::string::npos) << e;
  const auto msh = tempFile("lamina-garbage.msh", "$MeshFormat\nthis is not a mesh\n");
  const auto e2 = errorOf(
      replaced(kGood, "Lx = 1.0\nnx = 4", "type = \"gmsh\"\nfile = \"" + msh.string() + "\""));
  EXPECT_NE(e2.find("lamina-garbage.msh"), std::string::npos) << e2;
  std::filesystem::remove(geo);
  std::filesystem::remove(msh);
}

TEST(MembraneMalformed, UnknownMaterialListsWhatTheLibraryHas) {
  const auto lib = test::tempPath("lamina-membrane-test-library.toml");
  std::filesystem::remove(lib);
  lamina::materials::Material m;
  m.name = "my-fabric";
  m.C = lamina::materials::Stiffness::isotropic(2e9, 0.3);
  m.density = 1200;
  m.kind = "constants";
  lamina::materials::Library(lib).add(m);
  const std::string text =
      replaced(kGood, "E = 1.0e9\nnu = 0.3\ndensity = 1000.0", "material = \"no-such-fabric\"");
  std::string e;
  try {
    buildModel(lamina::core::parseTomlString(text, "bad.toml"), "bad.toml",
               {lib.string(), test::sourcePath("materials/catalog.toml").string()});
  } catch (const lamina::Error& err) {
    e = err.what();
  }
  EXPECT_NE(e.find("no-such-fabric"), std::string::npos) << e;
  EXPECT_NE(e.find("my-fabric"), std::string::npos) << e;
  EXPECT_NE(e.find("section"), std::string::npos) << e;
  std::filesystem::remove(lib);
  std::filesystem::remove(lib.string() + ".lock");
}

TEST(MembraneMalformed, SelectorsThatSelectNothingAreNamed) {
  const auto e = errorOf(kGood + "[[fixed]]\nnodes = \"rim\"\n");
  EXPECT_NE(e.find("rim"), std::string::npos) << e;
  EXPECT_NE(e.find("edges"), std::string::npos) << e; // lists the sets it has
}

TEST(MembraneMalformed, LoadTypeAndTargetNameTheKeyAndTheirChoices) {
  // The names are those of docs/membrane.md, "Loads".
  const std::string load = "[[load]]\ntype = \"force\"\nvalue = 1.0\nall = true\n";
  EXPECT_EQ(errorOf(kGood + load), "");
  auto e = errorOf(kGood + replaced(load, "\"force\"", "\"forse\""));
  EXPECT_NE(e.find("bad.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("load[0].type"), std::string::npos) << e;
  EXPECT_NE(e.find("\"forse\""), std::string::npos) << e;
  EXPECT_NE(e.find("\"force\", \"pressure\" or \"distributed\""), std::string::npos) << e;
  e = errorOf(kGood + replaced(load, "type = \"force\"\n", ""));
  EXPECT_NE(e.find("load[0].type"), std::string::npos) << e;
  EXPECT_NE(e.find("missing"), std::string::npos) << e;
  e = errorOf(kGood + load + "target = \"edges\"\n");
  EXPECT_NE(e.find("load[0].target"), std::string::npos) << e;
  EXPECT_NE(e.find("\"elements\" or \"nodes\""), std::string::npos) << e;
}

TEST(MembraneMalformed, DragRefusesASelectorOtherThanARegion) {
  // docs/membrane.md: drag acts on surface regions (or on all elements)
  const std::string drag = "[[drag]]\ncd = 1.0\n";
  for (const char* sel : {"box = [-1.0, 1.0, -1.0, 1.0]\n", "at = [0.0, 0.0]\n"}) {
    const auto e = errorOf(kGood + drag + sel);
    EXPECT_NE(e.find("bad.toml"), std::string::npos) << e;
    EXPECT_NE(e.find("drag[0]"), std::string::npos) << e;
    EXPECT_NE(e.find("give region = NAME"), std::string::npos) << e;
  }
}
