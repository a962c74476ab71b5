// Micro-inertia where it cannot act (refusals of hostile input): the
// gradient mass M_D has zero row sums (B of a rigid translation is
// 0), so lumping it, as the explicit scheme and the large-deflection model
// do, would drop it silently. Both are refused with the file and the key;
// micro_inertia = false in the section runs them without it.
#include "helpers.hpp"

#include <gtest/gtest.h>

using namespace lamina::membrane;

namespace {

/// A small clamped square of a section with an inline dispersion, with
/// @p head before the tables and @p section_extra in the section.
std::string dispersiveCase(const std::string& head, const std::string& time,
                           const std::string& section_extra = "") {
  return head +
         "[mesh]\nLx = 0.1\nnx = 4\n[[section]]\nE = 1e9\nnu = 0.3\ndensity = 1000.0\n"
         "thickness = 1e-3\ndispersion = [[0.02, 0, 0, 0, 0, 0], [0, 0.01, 0, 0, 0, 0], "
         "[0, 0, 0, 0, 0, 0], [0, 0, 0, 0.001, 0, 0], [0, 0, 0, 0, 0.001, 0], "
         "[0, 0, 0, 0, 0, 0.001]]\n" +
         section_extra + "[time]\n" + time + "t_end = 1e-5\n[[fixed]]\nnodes = \"edges\"\n";
}

std::string errorOf(const std::string& text) {
  return test::buildError(text, "micro.toml");
}

} // namespace

TEST(MalformedMicroInertia, ExplicitSchemeRefusesMicroInertia) {
  test::expectHas(errorOf(dispersiveCase("", "integrator = \"explicit\"\n")),
                  {"micro.toml", "time.integrator", "section[0]", "micro-inertia", "newmark"});
  // Without it the explicit run is accepted and steps.
  const Model m = test::modelFromText(
      dispersiveCase("", "integrator = \"explicit\"\n", "micro_inertia = false\n"), "micro.toml");
  Simulation sim(m);
  sim.step();
  EXPECT_EQ(sim.steps(), 1);
  // The scheme itself refuses a structure with M_D however it is reached.
  Model forced = test::modelFromText(dispersiveCase("", "dt = 1e-6\n"), "micro.toml");
  forced.time.integrator = IntegratorKind::Explicit;
  try {
    Simulation s(forced);
    ADD_FAILURE() << "the explicit scheme accepted micro-inertia";
  } catch (const lamina::Error& e) {
    EXPECT_NE(std::string(e.what()).find("micro-inertia"), std::string::npos) << e.what();
  }
}

TEST(MalformedMicroInertia, LargeDeflectionModelRefusesMicroInertia) {
  test::expectHas(errorOf(dispersiveCase("model = \"large_deflection\"\n", "")),
                  {"micro.toml", "section[0]", "micro-inertia", "micro_inertia = false"});
  EXPECT_EQ(
      errorOf(dispersiveCase("model = \"large_deflection\"\n", "", "micro_inertia = false\n")), "");
}
