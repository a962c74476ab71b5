// Malformed yarns (shape = "yarn"): each error names the file, the key or
// the group, and says what is wrong.

#include "core/error.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

namespace lamina::micro {
namespace {

// a scale-free unit cube, 8 voxels per edge
const std::string kHead = "[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = "
                          "\"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n[[phases]]\nname = "
                          "\"y\"\nlaw = \"isotropic\"\nE = 9e9\nnu = 0.2\ndensity = 2000\n";

std::string yarn(const std::string& keys) {
  return "[[inclusions]]\nphase = \"y\"\nshape = \"yarn\"\n" + keys + "\n";
}

void expectError(const std::string& text, const std::string& key, const std::string& words) {
  try {
    buildCell(readCellString(text, "weave.toml", lazyCatalog()));
    FAIL() << "no error for key " << key;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("weave.toml"), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

const std::string kWarp = "direction = \"x\"\nwidth = 0.4\nthickness = 0.1\n";

TEST(MalformedYarn, CrossingYarnsThatIntersectAreRefused) {
  // straight warp and weft through the same point: they intersect
  expectError(kHead + yarn(kWarp) + yarn("direction = \"y\"\nwidth = 0.4\nthickness = 0.1\n"),
              "inclusions[1]", "overlaps");
  // crimped, but 2 A = 0.08 below the thickness 0.1: still touching at the crossing
  expectError(kHead + yarn(kWarp + "amplitude = 0.04\ncenter = [0, 0.25, 0.5]") +
                  yarn("direction = \"y\"\nwidth = 0.4\nthickness = 0.1\namplitude = "
                       "0.04\ncenter = [0.25, 0.5, 0.5]"),
              "inclusions[1]", "overlaps");
}

TEST(MalformedYarn, ThicknessAndCrimpLargerThanTheCell) {
  expectError(kHead + yarn(kWarp + "amplitude = 0.46"), "inclusions[0]", "along axis z");
  expectError(kHead + yarn("direction = \"x\"\nwidth = 1.2\nthickness = 0.1"), "inclusions[0]",
              "along axis y");
}

TEST(MalformedYarn, WavelengthMustDivideTheCell) {
  expectError(kHead + yarn(kWarp + "amplitude = 0.1\nwavelength = 0.3"), "wavelength", "divide");
  expectError(kHead + yarn(kWarp + "amplitude = 0.1\nwavelength = 2.0"), "wavelength", "divide");
  expectError(kHead + yarn(kWarp + "wavelength = -1"), "wavelength", "positive");
}

TEST(MalformedYarn, SectionFoldingOverItsPathIsRefused) {
  // radius of curvature 1 / (A k^2) = 1 / (0.2 (2 pi / 0.25)^2) = 0.0079 < t / 2 = 0.05
  expectError(kHead + yarn("direction = \"x\"\nwidth = 0.2\nthickness = 0.1\namplitude = "
                           "0.2\nwavelength = 0.25"),
              "inclusions[0]", "radius of curvature");
}

TEST(MalformedYarn, BadDirectionCrimpAndAmplitude) {
  expectError(kHead + yarn("direction = [1, 1, 0]\nwidth = 0.2\nthickness = 0.1"), "direction",
              "cell axis");
  expectError(kHead + yarn(kWarp + "crimp = \"x\""), "crimp", "differ");
  expectError(kHead + yarn(kWarp + "crimp = \"w\""), "crimp", "unknown value");
  expectError(kHead + yarn("direction = \"z\"\nwidth = 0.2\nthickness = 0.1"), "crimp", "required");
  expectError(kHead + yarn(kWarp + "amplitude = -0.1"), "amplitude", "negative");
  expectError(kHead + yarn("direction = \"x\"\nthickness = 0.1"), "width", "");
  expectError(kHead + yarn(kWarp + "placement = \"random\"\ncount = 2"), "placement", "single");
  expectError(kHead + yarn(kWarp + "radius = 0.1"), "radius", "");
}

TEST(MalformedYarn, FollowPathMustBeABooleanOnAYarn) {
  expectError(kHead + yarn(kWarp + "follow_path = \"yes\""), "follow_path", "");
  expectError(kHead + yarn(kWarp + "follow_path = 1"), "follow_path", "");
  // not a key of other shapes
  expectError(kHead + "[[inclusions]]\nphase = \"y\"\nshape = \"fiber\"\ndirection = \"x\"\n"
                      "radius = 0.1\nfollow_path = true\n",
              "follow_path", "");
}

TEST(MalformedYarn, NonFiniteAndHugeSizesAreRefused) {
  // NaN and infinity never reach the geometry: the reader names the key
  expectError(kHead + yarn("direction = \"x\"\nwidth = nan\nthickness = 0.1"), "width", "finite");
  expectError(kHead + yarn(kWarp + "amplitude = inf"), "amplitude", "finite");
  expectError(kHead + yarn(kWarp + "wavelength = nan"), "wavelength", "finite");
  // a huge wavelength is a vanishing number of periods per cell, a huge width
  // does not fit: both refused, not overflowed
  expectError(kHead + yarn(kWarp + "amplitude = 0.1\nwavelength = 1e300"), "wavelength", "divide");
  expectError(kHead + yarn("direction = \"x\"\nwidth = 1e300\nthickness = 0.1"), "inclusions[0]",
              "along axis y");
}

} // namespace
} // namespace lamina::micro
