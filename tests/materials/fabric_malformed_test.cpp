// Bad fabric-law input: each error a lamina::Error naming the key and, for a
// stress-strain curve, the CSV file and its line.
#include "test_support.hpp"

#include "core/error.hpp"
#include "core/toml_reader.hpp"
#include "materials/law_spec.hpp"

#include <gtest/gtest.h>

namespace mat = lamina::materials;
using lamina::test::TempDir;
using lamina::test::writeFile;

namespace {

/// The error of reading law keys @p keys from "fabric.toml" in @p dir ("" if read).
std::string lawError(const TempDir& dir, const std::string& keys) {
  const std::string file = (dir / "fabric.toml").string();
  return lamina::test::errorOf([&] {
    const toml::table doc = lamina::core::parseTomlString("law = \"fabric\"\n" + keys, file);
    const lamina::core::TableReader t(doc, file);
    (void)mat::readLawSpec(t).make();
  });
}

/// The error of a fabric whose warp yarn is the curve file holding @p csv.
std::string curveError(const TempDir& dir, const std::string& csv) {
  writeFile(dir / "warp.csv", csv);
  return lawError(dir, "warp_curve = \"warp.csv\"\nE_fill = 4e8\nG12 = 1e7\n");
}

void expectHas(const std::string& message, const std::vector<std::string>& parts) {
  ASSERT_FALSE(message.empty()) << "accepted";
  for (const auto& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << "no '" << p << "' in: " << message;
}

} // namespace

TEST(FabricMalformed, TheGoodInputIsRead) {
  const TempDir dir;
  EXPECT_EQ(lawError(dir, "E_warp = 6e8\nE_fill = 5e8\nG12 = 2e7\n"), "");
  EXPECT_EQ(curveError(dir, "strain,stress\n0,0\n0.01,1e6\n0.02,1e6\n"),
            ""); // a flat part is monotone
}

TEST(FabricMalformed, ACurveThatIsNotMonotoneNamesFileLineAndKey) {
  const TempDir dir;
  expectHas(curveError(dir, "strain,stress\n0,0\n0.01,2e6\n0.02,1e6\n"),
            {"warp.csv:4", "warp_curve", "monotone"});
  expectHas(curveError(dir, "0,0\n0.02,1e6\n0.01,2e6\n"),
            {"warp.csv:3", "warp_curve", "does not increase"});
  expectHas(curveError(dir, "0,0\n0.02,1e6\n0.02,2e6\n"),
            {"warp.csv:3", "warp_curve", "does not increase"});
}

TEST(FabricMalformed, ACurveOfOnePointIsRefused) {
  const TempDir dir;
  expectHas(curveError(dir, "strain,stress\n0.01,1e6\n"),
            {"warp.csv:2", "warp_curve", "at least two"});
  expectHas(curveError(dir, "# empty\n"), {"warp.csv", "warp_curve", "at least two"});
}

TEST(FabricMalformed, ANonNumericCellNamesItsLine) {
  const TempDir dir;
  expectHas(curveError(dir, "strain,stress\n0,0\n0.01,abc\n"),
            {"warp.csv:3", "warp_curve", "two numbers"});
  expectHas(curveError(dir, "0,0\n0.01,1e6,7\n"), {"warp.csv:2", "warp_curve", "two numbers"});
  expectHas(curveError(dir, "0,0\n0.01,nan\n"), {"warp.csv:2", "warp_curve"});
  expectHas(curveError(dir, "0,0\n0.01,1e999\n"), {"warp.csv:2", "warp_curve"});
}

TEST(FabricMalformed, ABadFirstPointIsRefused) {
  const TempDir dir;
  expectHas(curveError(dir, "0,1e5\n0.01,1e6\n"), {"warp.csv:1", "warp_curve", "zero strain"});
  expectHas(curveError(dir, "-0.01,0\n0.01,1e6\n"), {"warp.csv:1", "warp_curve", "compression"});
  expectHas(curveError(dir, "0,0\n0.01,0\n"), {"warp_curve", "carries no stress"});
}

TEST(FabricMalformed, AMissingCurveFileIsNamed) {
  const TempDir dir;
  expectHas(lawError(dir, "warp_curve = \"nowhere.csv\"\nE_fill = 4e8\nG12 = 1e7\n"),
            {"nowhere.csv", "warp_curve"});
  expectHas(lawError(dir, "warp_curve = \"\"\nE_fill = 4e8\nG12 = 1e7\n"),
            {"fabric.toml", "warp_curve", "CSV"});
}

TEST(FabricMalformed, ABadModulusNamesItsKey) {
  const TempDir dir;
  expectHas(lawError(dir, "E_warp = -6e8\nE_fill = 5e8\nG12 = 2e7\n"),
            {"fabric.toml", "E_warp", "positive"});
  expectHas(lawError(dir, "E_warp = 6e8\nE_fill = 0.0\nG12 = 2e7\n"),
            {"fabric.toml", "E_fill", "positive"});
  expectHas(lawError(dir, "E_warp = 6e8\nE_fill = 5e8\nG12 = -2e7\n"),
            {"fabric.toml", "G12", "positive"});
  expectHas(lawError(dir, "E_warp = nan\nE_fill = 5e8\nG12 = 2e7\n"), {"fabric.toml", "E_warp"});
  expectHas(lawError(dir, "E_warp = 6e8\nE_fill = 5e8\nG12 = inf\n"), {"fabric.toml", "G12"});
}

TEST(FabricMalformed, MissingOrDoubledYarnAndCouplingAreRefused) {
  const TempDir dir;
  expectHas(lawError(dir, "E_warp = 6e8\nG12 = 2e7\n"), {"fabric.toml", "E_fill", "fill_curve"});
  writeFile(dir / "warp.csv", "0,0\n0.01,1e6\n");
  expectHas(lawError(dir, "E_warp = 6e8\nwarp_curve = \"warp.csv\"\nE_fill = 5e8\nG12 = 2e7\n"),
            {"fabric.toml", "warp_curve", "not both"});
  expectHas(lawError(dir, "E_warp = 6e8\nE_fill = 5e8\nG12 = 2e7\nnu12 = 0.3\n"),
            {"fabric.toml", "nu12", "must be 0"});
  expectHas(lawError(dir, "E_warp = 6e8\nE_fill = 5e8\n"), {"fabric.toml", "G12"});
}
