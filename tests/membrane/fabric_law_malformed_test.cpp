// A fabric-law section where it cannot act: the linear (paper's) model and
// wrinkling on top of it are refused naming the key; the catalog's roof
// fabric builds as a section's material with its own thickness.
#include "helpers.hpp"

#include <gtest/gtest.h>

using namespace lamina::membrane;
using test::expectHas;

namespace {

const std::string kFabric = "law = \"fabric\"\nE_warp = 6.4e8\nE_fill = 5.2e8\nG12 = 2.8e7\n"
                            "density = 1283.0\n";

std::string errorOf(const std::string& text) {
  return test::buildError(text, "fabric.toml");
}

} // namespace

TEST(FabricLawMalformed, TheGoodSheetsBuild) {
  EXPECT_EQ(errorOf(test::sectionSheet(kFabric)), "");
  EXPECT_EQ(errorOf(test::sectionSheet("material = \"vinyl-coated-polyester\"\n")), "");
}

TEST(FabricLawMalformed, TheLinearModelRefusesTheFabricLaw) {
  expectHas(errorOf(test::sectionSheet(kFabric, "linear")),
            {"fabric.toml", "nonlinear law", "fabric", "model = \"large_deflection\""});
  expectHas(
      errorOf(test::sectionSheet("material = \"vinyl-coated-polyester\"\n", "linear")),
      {"fabric.toml", "nonlinear law", "vinyl-coated-polyester", "model = \"large_deflection\""});
}

TEST(FabricLawMalformed, WrinklingOnTopOfTheFabricIsRefused) {
  expectHas(errorOf(test::sectionSheet(kFabric + "tension_only = true\n")),
            {"fabric.toml", "section[0].tension_only", "fabric law"});
}

TEST(FabricLawMalformed, AKeyOfAnotherLawIsNamed) {
  expectHas(errorOf(test::sectionSheet(kFabric + "nu = 0.3\n")),
            {"fabric.toml", "section[0].nu", "not a key of law \"fabric\""});
}

TEST(FabricLawMalformed, AMissingCurveFileNamesTheSectionKey) {
  expectHas(errorOf(test::sectionSheet(
                "law = \"fabric\"\nwarp_curve = \"no-such-curve.csv\"\nE_fill = 5.2e8\n"
                "G12 = 2.8e7\ndensity = 1283.0\n")),
            {"no-such-curve.csv", "section[0].warp_curve"});
}

TEST(FabricLawMalformed, TheCatalogThicknessIsTheSectionsDefault) {
  const std::string sheet = "model = \"large_deflection\"\n[mesh]\nLx = 0.1\nnx = 2\n[[section]]\n"
                            "material = \"vinyl-coated-polyester\"\n[time]\nintegrator = "
                            "\"explicit\"\nt_end = 1.0e-5\n[[fixed]]\nnodes = \"edges\"\n";
  const Model m = test::modelFromText(sheet);
  ASSERT_EQ(m.sections.size(), 1u);
  EXPECT_EQ(m.sections[0].thickness, 0.53e-3);
  EXPECT_EQ(m.sections[0].law->kind(), lamina::materials::LawKind::Fabric);
}
