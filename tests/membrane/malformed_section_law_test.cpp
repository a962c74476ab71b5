// Malformed [[section]] laws: each error names the file, the section's key
// and the cause, in the messages of the one law reader (materials::
// readLawSpec) where it is the reader's; a nonlinear law where it cannot act
// (the linear model, micro-inertia, a layup) is refused naming the region.
#include "helpers.hpp"

#include "../core/test_util.hpp"
#include "../materials/reduced_order_cells.hpp"
#include "membrane/model/linear_membrane.hpp"

#include <gtest/gtest.h>

using namespace lamina::membrane;
using test::expectHas;

namespace {

std::string errorOf(const std::string& text) {
  return test::buildError(text, "law.toml");
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

/// The error of building @p text with a library holding the reduced-order
/// polyurea laminate as entry "pu-cell" ("" when it builds).
std::string errorWithReducedOrderEntry(const std::string& text) {
  const lamina::test::TempDir dir; // the library, its lock and its side files
  lamina::test::addReducedOrderEntry(dir / "library.toml", "pu-cell",
                                     lamina::test::polyureaLaminate());
  try {
    test::modelWithLibrary(text, dir / "library.toml");
  } catch (const lamina::Error& err) {
    return err.what();
  }
  return "";
}

const std::string kIsotropicC =
    "C = [[1.0e9, 0, 0, 0, 0, 0], [0, 1.0e9, 0, 0, 0, 0], [0, 0, 1.0e9, 0, 0, 0], "
    "[0, 0, 0, 1.0e9, 0, 0], [0, 0, 0, 0, 1.0e9, 0], [0, 0, 0, 0, 0, 1.0e9]]\n";

} // namespace

TEST(MalformedSectionLaw, TheGoodSheetsBuild) {
  // the mutations below are refused for their own fault, not the sheet's
  EXPECT_EQ(errorOf(test::sectionSheet(test::gvboTable5Keys())), "");
  EXPECT_EQ(errorOf(test::sectionSheet("material = \"polyurea-gvbo\"\n")), "");
  EXPECT_EQ(errorOf(test::sectionSheet("law = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1e3\n",
                                       "linear")),
            "");
  EXPECT_EQ(errorWithReducedOrderEntry(test::sectionSheet("material = \"pu-cell\"\n")), "");
}

TEST(MalformedSectionLaw, AKeyTheLawDoesNotTakeIsNamed) {
  expectHas(errorOf(test::sectionSheet("law = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1e3\n" +
                                       kIsotropicC)),
            {"law.toml", "section[0].C", "not a key of law \"isotropic\""});
  expectHas(errorOf(test::sectionSheet(
                replaced(test::gvboTable5Keys(), "law = \"gvbo\"", "law = \"isotropic\""))),
            {"law.toml", "section[0].gvbo", "not a key of law \"isotropic\""});
  // the shortcut E means law "isotropic": E1 is transversely isotropic's
  expectHas(errorOf(test::sectionSheet("E = 1e9\nnu = 0.3\nE1 = 2e9\ndensity = 1e3\n")),
            {"law.toml", "section[0].E1", "not a key of law \"isotropic\""});
}

TEST(MalformedSectionLaw, ExactlyOneSourceOfTheLawListsThem) {
  for (const std::string& keys :
       {std::string("material = \"polyurea-gvbo\"\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\n"),
        "E = 1e9\nnu = 0.3\ndensity = 1e3\n" + kIsotropicC, std::string("density = 1e3\n")})
    expectHas(errorOf(test::sectionSheet(keys)),
              {"law.toml", "section[0]", "exactly one of material, law", "E (with nu", "C (with",
               "plies"});
}

TEST(MalformedSectionLaw, GvboParameterNanOrOutOfRangeNamesFileAndKey) {
  const std::string gvbo = test::gvboTable5Keys();
  expectHas(errorOf(test::sectionSheet(replaced(gvbo, "Et = 23.3e6", "Et = nan"))),
            {"law.toml", "section[0].gvbo.Et", "finite", "nan"});
  // Et at E0 leaves no hardening (chapter Table 1: Et < E); k1 is a time
  expectHas(errorOf(test::sectionSheet(replaced(gvbo, "Et = 23.3e6", "Et = 278.0e6"))),
            {"law.toml", "section[0].gvbo", "Et must lie in [0, E0)"});
  expectHas(errorOf(test::sectionSheet(replaced(gvbo, "k1 = 17.0", "k1 = -17.0"))),
            {"law.toml", "section[0].gvbo", "k1 must be positive"});
  expectHas(errorOf(test::sectionSheet(replaced(gvbo, "nu = 0.491", "nu = 0.5"))),
            {"law.toml", "section[0].nu", "(-1, 0.5)"});
  expectHas(errorOf(test::sectionSheet(replaced(gvbo, "k2 = 0.47e6, ", ""))),
            {"law.toml", "section[0].gvbo.k2", "missing"});
}

TEST(MalformedSectionLaw, UnknownLawListsTheLaws) {
  expectHas(errorOf(test::sectionSheet(
                replaced(test::gvboTable5Keys(), "law = \"gvbo\"", "law = \"gbvo\""))),
            {"law.toml", "section[0].law", "'gbvo'",
             "'isotropic', 'transversely-isotropic', 'anisotropic', 'gvbo' or 'fabric'"});
  // a reduced-order cell is a library entry, given by its name
  expectHas(errorOf(test::sectionSheet("law = \"reduced-order\"\ndensity = 1e3\n")),
            {"law.toml", "section[0].law", "library entry"});
}

TEST(MalformedSectionLaw, NonlinearLawUnderTheLinearModelNamesRegionAndLargeDeflection) {
  expectHas(errorOf(test::sectionSheet(test::gvboTable5Keys(), "linear")),
            {"law.toml", "section[0]", "region 'all'", "inline gvbo", "nonlinear",
             "model = \"large_deflection\""});
  expectHas(errorOf(test::sectionSheet("material = \"polyurea-gvbo\"\n", "linear")),
            {"law.toml", "section[0]", "region 'all'", "polyurea-gvbo (gvbo)",
             "model = \"large_deflection\""});
  expectHas(errorWithReducedOrderEntry(test::sectionSheet("material = \"pu-cell\"\n", "linear")),
            {"test.toml", "section[0]", "region 'all'", "pu-cell (reduced-order)",
             "model = \"large_deflection\""});
}

TEST(MalformedSectionLaw, LinearMembraneBuiltByHandRefusesANonlinearSection) {
  // a model built in code skips the case reader: the model checks itself
  const Model model = test::modelFromText(test::sectionSheet("material = \"polyurea-gvbo\"\n"));
  std::string e;
  try {
    LinearMembrane m(model, model.time.lumped);
  } catch (const lamina::Error& err) {
    e = err.what();
  }
  expectHas(e, {"section 'all'", "polyurea-gvbo (gvbo)", "nonlinear law (gvbo)",
                "model = \"large_deflection\""});
}

TEST(MalformedSectionLaw, NonlinearLawWithMicroInertiaNamesTheRegion) {
  const std::string dispersion = "dispersion = [[0.02, 0, 0, 0, 0, 0], [0, 0.01, 0, 0, 0, 0], "
                                 "[0, 0, 0, 0, 0, 0], [0, 0, 0, 0.001, 0, 0], "
                                 "[0, 0, 0, 0, 0.001, 0], [0, 0, 0, 0, 0, 0.001]]\n";
  expectHas(errorOf(test::sectionSheet(test::gvboTable5Keys() + dispersion)),
            {"law.toml", "section[0]", "region 'all'", "inline gvbo", "micro-inertia",
             "micro_inertia = false"});
}

TEST(MalformedSectionLaw, NonlinearPlyInALayupIsRefused) {
  expectHas(errorOf(test::sectionSheet(
                "plies = [\"aramid:0:0.5e-3\", \"polyurea-gvbo:90:0.5e-3\"]\n", "linear")),
            {"law.toml", "section[0].plies", "'polyurea-gvbo'", "nonlinear law (gvbo)",
             "linear laminate of elastic plies"});
  expectHas(errorWithReducedOrderEntry(
                test::sectionSheet("plies = [\"aramid:0:0.5e-3\", \"pu-cell:90:0.5e-3\"]\n")),
            {"test.toml", "section[0].plies", "'pu-cell'", "nonlinear law (reduced-order)",
             "linear laminate of elastic plies"});
}

TEST(MalformedSectionLaw, InlineLawWithoutDensityIsNamed) {
  expectHas(errorOf(test::sectionSheet(replaced(test::gvboTable5Keys(), "density = 1100.0\n", ""))),
            {"law.toml", "section[0].density", "missing"});
  expectHas(errorOf(test::sectionSheet("law = \"isotropic\"\nE = 1e9\nnu = 0.3\n")),
            {"law.toml", "section[0].density", "missing"});
}

namespace {

/// The error of building @p section's sheet with an empty library in a
/// temporary folder ("" when it builds); @p library receives its path.
std::string errorWithEmptyLibrary(const std::string& section, std::string& library) {
  const lamina::test::TempDir dir;
  library = (dir / "library.toml").string();
  try {
    test::modelWithLibrary(test::sectionSheet(section, "linear"), library);
  } catch (const lamina::Error& err) {
    return err.what();
  }
  return "";
}

} // namespace

// A material in neither the library nor the catalog: the error names the
// library file searched and how to make the entry; with `material_from`
// (the cell file, relative to the case file: the helper's case file is
// cases/membrane/test.toml) the very homogenize command, into that library.
TEST(MalformedSectionLaw, AnUnknownMaterialNamesTheCommandThatMakesIt) {
  std::string lib;
  const std::string cell = std::string(LAMINA_SOURCE_DIR) + "/cases/cells/laminate.toml";
  std::string error = errorWithEmptyLibrary("material = \"steel-pu-laminate\"\n"
                                            "material_from = \"../cells/laminate.toml\"\n",
                                            lib);
  expectHas(error,
            {"test.toml", "section[0].material", "steel-pu-laminate", "not in library " + lib,
             "catalog",
             "make it with: homogenize " + cell + " --name steel-pu-laminate --library " + lib});
  // without material_from: the generic command, and where to look
  error = errorWithEmptyLibrary("material = \"steel-pu-laminate\"\n", lib);
  expectHas(error, {"section[0].material", "not in library " + lib,
                    "homogenize CELL.toml --name steel-pu-laminate --library " + lib,
                    "materials --library " + lib + " list"});
  // a material the catalog has builds: material_from is read only when needed
  EXPECT_EQ(errorWithEmptyLibrary("material = \"vinyl-fabric\"\n"
                                  "material_from = \"../cells/no-such-cell.toml\"\n",
                                  lib),
            "");
  // a cell file that does not exist, or material_from without a material
  expectHas(errorWithEmptyLibrary("material = \"steel-pu-laminate\"\n"
                                  "material_from = \"../cells/no-such-cell.toml\"\n",
                                  lib),
            {"section[0].material_from", "no-such-cell.toml", "does not exist"});
  expectHas(errorWithEmptyLibrary("E = 1e9\nnu = 0.3\ndensity = 1e3\n"
                                  "material_from = \"../cells/laminate.toml\"\n",
                                  lib),
            {"section[0].material_from", "material = \"NAME\""});
}
