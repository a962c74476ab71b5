// Malformed cell files: each error names the file and the offending key.

#include "core/error.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

namespace lamina::micro {
namespace {

const std::string kHead = "[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = "
                          "\"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n[[phases]]\nname = "
                          "\"i\"\nlaw = \"isotropic\"\nE = 9e9\nnu = 0.2\ndensity = 2000\n";

// Expects readCellString (and buildCell) to throw an Error whose message
// names the file "bad.toml" and contains @p key and @p words.
void expectError(const std::string& text, const std::string& key, const std::string& words = "") {
  try {
    const CellSpec s = readCellString(text, "bad.toml", lazyCatalog());
    buildCell(s);
    FAIL() << "no error for key " << key;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.toml"), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(MalformedCell, UnknownKeyIsNamed) {
  expectError(kHead +
                  "[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\nradius = 0.1\nradus = 2\n",
              "radus");
}

TEST(MalformedCell, NegativeRadius) {
  expectError(kHead + "[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\nradius = -0.1\n",
              "radius", "positive");
}

TEST(MalformedCell, UnknownPhaseShapeAndPlacement) {
  expectError(kHead + "[[inclusions]]\nphase = \"x\"\nshape = \"sphere\"\nradius = 0.1\n", "phase");
  expectError(kHead + "[[inclusions]]\nphase = \"i\"\nshape = \"cube\"\nradius = 0.1\n", "shape");
  expectError(kHead + "[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\nradius = "
                      "0.1\nplacement = \"grid\"\n",
              "placement");
}

TEST(MalformedCell, BadPhaseLaws) {
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = "
              "1e9\nnu = 0.5\ndensity = 1000\n",
              "nu");
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = "
              "1e9\nnu = 0.3\ndensity = -1\n",
              "density");
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = "
              "1e9\nnu = 0.3\ndensity = 1000\nJ = 0.9\n",
              "J", "gvbo");
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = \"anisotropic\"\nC = [[1, "
              "0], [0, 1]]\ndensity = 1000\n",
              "C");
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = \"rubber\"\ndensity = "
              "1000\n",
              "law");
}

// A cell's size is in metres: an edge above 0.1 m cannot be a
// unit cell (and is most likely a unit-less size from before), so it is an
// error that says so; no size is a scale-free cell.
TEST(MalformedCell, SizeIsInMetres) {
  expectError("[cell]\nresolution = 8\nsize = [1.0, 1.0, 1.0]\n" + kHead.substr(22), "size",
              "metres");
  const CellSpec none = readCellString(kHead, "ok.toml", lazyCatalog());
  EXPECT_FALSE(none.physical_size);
  const CellSpec given = readCellString("[cell]\nresolution = 8\nsize = 2e-5\n" + kHead.substr(22),
                                        "ok.toml", lazyCatalog());
  EXPECT_TRUE(given.physical_size);
  EXPECT_EQ(given.size, Eigen::Vector3d::Constant(2e-5));
}

TEST(MalformedCell, BadResolutionAndFraction) {
  expectError("[cell]\nresolution = 1\n[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = "
              "1e9\nnu = 0.3\ndensity = 1000\n",
              "resolution");
  expectError(kHead + "[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\nradius = "
                      "0.1\nvolume_fraction = 1.5\n",
              "volume_fraction");
}

// A sphere too large for the cell and an infeasible random packing are
// reported for their inclusion group.
TEST(MalformedCell, InclusionsThatDoNotFit) {
  expectError(kHead + "[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\nradius = 0.6\n",
              "inclusions[0]", "does not fit");
  expectError(kHead + "[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\nradius = "
                      "0.1\nplacement = \"random\"\ncount = 200\nvolume_fraction = "
                      "0.6\nmax_attempts = 2000\n",
              "inclusions[0]", "random placement failed");
}

// composite_voxels is a boolean: a string or an integer (also 0 and 1) is
// refused naming the key, not read as true.
TEST(MalformedCell, CompositeVoxelsMustBeABoolean) {
  const std::string head = kHead.substr(0, kHead.find("[[phases]]"));
  const std::string phases = kHead.substr(kHead.find("[[phases]]"));
  for (const std::string bad : {"\"yes\"", "1", "0", "[true]"})
    expectError(head + "composite_voxels = " + bad + "\n" + phases, "cell.composite_voxels",
                "expected true or false");
}

// The fabric law is a membrane law: a cell phase refuses it, inline or
// from the catalog.
TEST(MalformedCell, FabricLawIsNotACellPhase) {
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = \"fabric\"\nE_warp = "
              "6e8\nE_fill = 5e8\nG12 = 3e7\ndensity = 1283\n",
              "phases[0].law", "membrane law");
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\ncatalog = "
              "\"vinyl-coated-polyester\"\n",
              "phases[0].catalog", "membrane law");
}

TEST(MalformedCell, MissingCatalogEntry) {
  expectError("[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\ncatalog = \"unobtainium\"\n",
              "catalog", "unobtainium");
}

} // namespace
} // namespace lamina::micro
