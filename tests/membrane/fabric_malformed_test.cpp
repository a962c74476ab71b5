// Malformed large-deflection and explicit-integrator keys: each error names
// the file, the key and the cause.
#include "helpers.hpp"

#include <gtest/gtest.h>

using namespace lamina::membrane;

namespace {
/// The error message of building @p text, or "" if it builds (or runs, with @p run).
std::string errorOf(const std::string& text, bool run = false) {
  try {
    const Model m = test::modelFromText(text, "bad.toml");
    if (run)
      Simulation sim(m);
  } catch (const lamina::Error& e) {
    return e.what();
  }
  return "";
}

const std::string kFixed = "[[fixed]]\nnodes = \"edges\"\n";

void expectNames(const std::string& e, const std::string& key, const std::string& cause) {
  EXPECT_NE(e.find("bad.toml"), std::string::npos) << e;
  EXPECT_NE(e.find(key), std::string::npos) << e;
  EXPECT_NE(e.find(cause), std::string::npos) << e;
}
} // namespace

TEST(FabricMalformed, GoodLargeDeflectionCaseBuilds) {
  EXPECT_EQ(errorOf("model = \"large_deflection\"\n" + test::isotropicSquare(4) +
                        "tension_only = true\nprestress = [10.0, 20.0, 0.0]\n"
                        "[time]\nt_end = 1.0e-4\n" +
                        kFixed,
                    true),
            "");
}

TEST(FabricMalformed, UnknownModelIsRejected) {
  expectNames(errorOf("model = \"nonlinear\"\n" + test::isotropicSquare(4) +
                      "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n"),
              "model", "large_deflection");
}

TEST(FabricMalformed, FabricKeysNeedTheLargeDeflectionModel) {
  for (const char* key : {"tension_only = true", "prestress = 10.0", "failure_strain = 0.1"}) {
    const auto e =
        errorOf(test::isotropicSquare(4) + key + "\n[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n");
    expectNames(e, "section", "large_deflection");
  }
}

TEST(FabricMalformed, LargeDeflectionRefusesNewmark) {
  expectNames(errorOf("model = \"large_deflection\"\n" + test::isotropicSquare(4) +
                      "[time]\nintegrator = \"newmark\"\ndt = 1.0e-5\nt_end = 1.0e-4\n"),
              "time.integrator", "explicit");
}

TEST(FabricMalformed, ExplicitKeysNeedTheExplicitIntegrator) {
  expectNames(
      errorOf(test::isotropicSquare(4) + "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\ndamping = 1.0\n"),
      "time.damping", "explicit");
}

// Springs and rigid sets are no longer explicit-only: Newmark takes both.
TEST(FabricMalformed, NewmarkTakesSpringsAndRigidSets) {
  EXPECT_EQ(errorOf(test::isotropicSquare(4) + "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n" +
                        "[[spring]]\nnodes = \"edges\"\nstiffness = 1.0e3\n"
                        "[[rigid]]\nnodes = \"left\"\n",
                    true),
            "");
}

TEST(FabricMalformed, ExplicitStepAboveTheStableStepIsRejected) {
  // Stable step of this mesh: about 3e-5 s (E = 1 GPa, 0.25 m elements);
  // 1e-3 s is far above it.
  const auto e = errorOf("model = \"large_deflection\"\n" + test::isotropicSquare(4) +
                             "[time]\ndt = 1.0e-3\nt_end = 1.0e-2\n",
                         true);
  EXPECT_NE(e.find("exceeds the stable step"), std::string::npos) << e;
}

TEST(FabricMalformed, BadSpringAndRigidSetsAreNamed) {
  const std::string base =
      "model = \"large_deflection\"\n" + test::isotropicSquare(4) + "[time]\nt_end = 1.0e-4\n";
  expectNames(errorOf(base + "[[spring]]\nnodes = \"edges\"\nstiffness = -1.0\n"),
              "spring[0].stiffness", "> 0");
  expectNames(errorOf(base + kFixed + "[[rigid]]\nnodes = \"left\"\n"), "rigid",
              "already constrained");
  expectNames(errorOf(base + "[[rigid]]\nnodes = \"left\"\ncomponents = \"zq\"\n"),
              "rigid[0].components", "xyz");
}

// The drag's area and normal variants: the large-deflection model's only
// (the linear model's flat membrane has one normal and fixed areas), and
// their values are the enums' names.
TEST(FabricMalformed, DragVariantKeysAreChecked) {
  const std::string linear =
      test::isotropicSquare(4) + "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n" + "[[drag]]\ncd = 1.5\n";
  expectNames(errorOf(linear + "area = \"reference\"\n"), "drag[0].area",
              "large-deflection model only");
  expectNames(errorOf(linear + "normal = \"element\"\n"), "drag[0].normal",
              "large-deflection model only");
  const std::string large = "model = \"large_deflection\"\n" + test::isotropicSquare(4) +
                            "[time]\nt_end = 1.0e-4\n" + kFixed + "[[drag]]\ncd = 1.5\n";
  expectNames(errorOf(large + "area = \"deformed\"\n"), "drag[0].area", "reference");
  expectNames(errorOf(large + "normal = \"face\"\n"), "drag[0].normal", "element");
  EXPECT_EQ(errorOf(large + "area = \"reference\"\nnormal = \"element\"\n", true), "");
}

TEST(FabricMalformed, BadFabricValuesAreNamed) {
  const std::string base = "model = \"large_deflection\"\n" + test::isotropicSquare(4);
  const std::string time = "[time]\nt_end = 1.0e-4\n";
  expectNames(errorOf(base + "prestress = [1.0, 2.0]\n" + time), "section[0].prestress", "T11");
  expectNames(errorOf(base + "failure_strain = -0.1\n" + time), "section[0].failure_strain", "> 0");
  expectNames(errorOf(base + "material_axis = [0.0, 0.0, 0.0]\n" + time),
              "section[0].material_axis", "non-zero");
  expectNames(errorOf(base + time + "safety = 1.5\n"), "time.safety", "(0, 1]");
}

// The section key `wrinkling` (the law of a tension-only section): an unknown
// name lists the valid ones; it needs model = "large_deflection" (like
// tension_only), tension_only = true, and "projection" needs an elastic law.
TEST(FabricMalformed, BadWrinklingKeyIsNamed) {
  const std::string lin = test::isotropicSquare(4);
  const std::string tail = "[time]\nt_end = 1.0e-4\n" + kFixed;
  const auto unknown = errorOf("model = \"large_deflection\"\n" + lin +
                               "tension_only = true\nwrinkling = \"relax\"\n" + tail);
  expectNames(unknown, "wrinkling", "relax");
  EXPECT_NE(unknown.find("\"relaxed\" or \"projection\""), std::string::npos) << unknown;
  expectNames(errorOf(lin + "wrinkling = \"relaxed\"\n" + tail), "wrinkling", "large_deflection");
  expectNames(
      errorOf("model = \"large_deflection\"\n" + lin + "wrinkling = \"projection\"\n" + tail),
      "wrinkling", "tension_only = true");
  expectNames(errorOf(test::sectionSheet(test::gvboTable5Keys() +
                                         "tension_only = true\nwrinkling = \"projection\"\n"),
                      true),
              "wrinkling", "needs an elastic law");
  // Both names build.
  for (const char* name : {"relaxed", "projection"})
    EXPECT_EQ(errorOf("model = \"large_deflection\"\n" + lin +
                          "tension_only = true\nwrinkling = \"" + name + "\"\n" + tail,
                      true),
              "");
}
