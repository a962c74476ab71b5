// Bad input to the library reader and to the `materials` program: every
// failure is a lamina::Error (or a non-zero exit with ONE line on stderr)
// naming the file, line, key or entry at fault, and the library file is
// byte-identical afterwards.

#include "core/error.hpp"
#include "materials/catalog.hpp"
#include "materials/library.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <functional>

namespace mat = lamina::materials;
using lamina::test::errorOf;
using lamina::test::readFile;
using lamina::test::runMaterials;
using lamina::test::TempDir;
using lamina::test::writeFile;

namespace {

// A valid library text with one isotropic entry; entry line numbers below
// refer to this layout.
const std::string kHeader = "[lamina]\n"                              // 1
                            "format = \"lamina-materials-library\"\n" // 2
                            "version = 1\n";                          // 3
const std::string kEntry = "[materials.steel]\n"                      // 4
                           "kind = \"catalog\"\n"                     // 5
                           "density = 7850.0\n"                       // 6
                           "C = [\n"                                  // 7
                           "  [2.8e11, 1.2e11, 1.2e11, 0.0, 0.0, 0.0],\n"
                           "  [1.2e11, 2.8e11, 1.2e11, 0.0, 0.0, 0.0],\n"
                           "  [1.2e11, 1.2e11, 2.8e11, 0.0, 0.0, 0.0],\n"
                           "  [0.0, 0.0, 0.0, 8e10, 0.0, 0.0],\n"
                           "  [0.0, 0.0, 0.0, 0.0, 8e10, 0.0],\n"
                           "  [0.0, 0.0, 0.0, 0.0, 0.0, 8e10],\n"
                           "]\n"; // 14

class LibraryFile : public ::testing::Test {
protected:
  std::string load(const std::string& text) {
    writeFile(path_, text);
    return errorOf([&] { mat::Library lib(path_); });
  }
  TempDir dir_;
  std::filesystem::path path_ = dir_ / "lib.toml";
};

} // namespace

// The fixture text itself is valid (so the failures below are due to the edits).
TEST_F(LibraryFile, ValidTextLoads) {
  EXPECT_EQ(load(kHeader + kEntry), "");
  EXPECT_EQ(mat::Library(path_).get("steel").C(3, 3), 8e10);
}

TEST_F(LibraryFile, MalformedTomlNamesFileAndLine) {
  const std::string msg = load(kHeader + "[materials.steel]\nkind = \"catalog\ndensity = 1.0\n");
  EXPECT_NE(msg.find(path_.string() + ":5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("malformed TOML"), std::string::npos) << msg;
}

TEST_F(LibraryFile, UnknownKeyNamesKeyAndLine) {
  std::string text = kHeader + kEntry + "colour = \"red\"\n"; // line 15
  std::string msg = load(text);
  EXPECT_NE(msg.find("materials.steel.colour"), std::string::npos) << msg;
  EXPECT_NE(msg.find(path_.string() + ":15"), std::string::npos) << msg;
  msg = load(kHeader + "extra = 1\n" + kEntry); // line 4, inside [lamina]
  EXPECT_NE(msg.find(path_.string() + ":4: 'lamina.extra'"), std::string::npos) << msg;
}

TEST_F(LibraryFile, WrongTypeAndMissingKeyNameTheKey) {
  std::string text = kHeader + kEntry;
  text.replace(text.find("7850.0"), 6, "\"heavy\"");
  std::string msg = load(text);
  EXPECT_NE(msg.find("materials.steel.density"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
  text = kHeader + kEntry;
  text.erase(text.find("density = 7850.0\n"), 17);
  msg = load(text);
  EXPECT_NE(msg.find("materials.steel.density"), std::string::npos) << msg;
  EXPECT_NE(msg.find("missing"), std::string::npos) << msg;
}

TEST_F(LibraryFile, BadMatrixShapeNamesTheKey) {
  std::string text = kHeader + kEntry;
  const std::string lastRow = "  [0.0, 0.0, 0.0, 0.0, 0.0, 8e10],\n";
  text.erase(text.find(lastRow), lastRow.size());
  const std::string msg = load(text);
  EXPECT_NE(msg.find("materials.steel.C"), std::string::npos) << msg;
  EXPECT_NE(msg.find("6 rows"), std::string::npos) << msg;
}

TEST_F(LibraryFile, NonPositiveDefiniteEntryNamesFileAndEntry) {
  std::string text = kHeader + kEntry;
  text.replace(text.find("[2.8e11"), 7, "[-2.8e11");
  const std::string msg = load(text);
  EXPECT_NE(msg.find(path_.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("materials.steel"), std::string::npos) << msg;
  EXPECT_NE(msg.find("positive definite"), std::string::npos) << msg;
}

// A bad density is blamed on the density key and its line (6), not on C.
TEST_F(LibraryFile, BadDensityNamesTheDensityKey) {
  for (const char* bad : {"-7850.0", "0.0", "nan", "inf"}) {
    std::string text = kHeader + kEntry;
    text.replace(text.find("7850.0"), 6, bad);
    const std::string msg = load(text);
    EXPECT_NE(msg.find(path_.string() + ":6: 'materials.steel.density'"), std::string::npos)
        << bad << ": " << msg;
  }
}

TEST_F(LibraryFile, BadThicknessNamesTheKey) {
  std::string text = kHeader + kEntry + "thickness = -1e-3\n"; // line 15
  std::string msg = load(text);
  EXPECT_NE(msg.find(path_.string() + ":15: 'materials.steel.thickness'"), std::string::npos)
      << msg;
  text = kHeader + kEntry + "plies = [{ material = \"a\", angle_deg = 0.0, thickness = 0.0 }]\n";
  msg = load(text);
  EXPECT_NE(msg.find("'materials.steel.plies[0].thickness'"), std::string::npos) << msg;
}

// A dispersion (micro-inertia) must be 6x6, symmetric and positive
// semi-definite; a cell size three positive lengths. Each names its key.
TEST_F(LibraryFile, BadDispersionAndCellSizeNameTheirKeys) {
  const std::string zero = "  [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],\n";
  auto dispersion = [&](const std::string& first_row, int rows) {
    std::string t = "dispersion = [\n" + first_row;
    for (int i = 1; i < rows; ++i)
      t += zero;
    return t + "]\n";
  };
  std::string msg = load(kHeader + kEntry + dispersion(zero, 5));
  EXPECT_NE(msg.find("'materials.steel.dispersion'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("6 rows"), std::string::npos) << msg;
  msg = load(kHeader + kEntry + dispersion("  [1e-3, 1e-4, 0.0, 0.0, 0.0, 0.0],\n", 6));
  EXPECT_NE(msg.find("'materials.steel.dispersion'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("symmetric"), std::string::npos) << msg;
  msg = load(kHeader + kEntry + dispersion("  [-1e-3, 0.0, 0.0, 0.0, 0.0, 0.0],\n", 6));
  EXPECT_NE(msg.find("'materials.steel.dispersion'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("semi-definite"), std::string::npos) << msg;
  msg = load(kHeader + kEntry + "cell_size = [1e-3, 0.0, 1e-3]\n");
  EXPECT_NE(msg.find("'materials.steel.cell_size'"), std::string::npos) << msg;
  msg = load(kHeader + kEntry + "cell_size = [1e-3, 1e-3]\n");
  EXPECT_NE(msg.find("'materials.steel.cell_size'"), std::string::npos) << msg;
  EXPECT_EQ(load(kHeader + kEntry + dispersion("  [1e-3, 0.0, 0.0, 0.0, 0.0, 0.0],\n", 6)), "");
}

TEST_F(LibraryFile, UnknownKindNamesTheKey) {
  std::string text = kHeader + kEntry;
  text.replace(text.find("\"catalog\""), 9, "\"magic\"");
  const std::string msg = load(text);
  EXPECT_NE(msg.find("materials.steel.kind"), std::string::npos) << msg;
}

// A catalog is validated as strictly as the library: an unknown key, an
// unknown law, a missing density or an indefinite C names file, line, entry.
TEST_F(LibraryFile, BadCatalogNamesFileLineAndEntry) {
  const std::string good = "[glass]\ndescription = \"d\"\nsource = \"s\"\ndensity = 2540.0\n"
                           "law = \"isotropic\"\nE = 72.4e9\nnu = 0.22\n";
  auto catalogError = [&](const std::string& text) {
    writeFile(path_, text);
    return errorOf([&] { mat::Catalog cat(path_); });
  };
  EXPECT_EQ(catalogError(good), "");
  std::string msg = catalogError(good + "colour = \"green\"\n"); // line 8
  EXPECT_NE(msg.find(path_.string() + ":8: 'glass.colour'"), std::string::npos) << msg;
  std::string text = good;
  text.replace(text.find("\"isotropic\""), 11, "\"plastic\"");
  msg = catalogError(text);
  EXPECT_NE(msg.find("'glass.law'"), std::string::npos) << msg;
  text = good;
  text.erase(text.find("density = 2540.0\n"), 17);
  msg = catalogError(text);
  EXPECT_NE(msg.find("'glass.density'"), std::string::npos) << msg;
  text = good;
  text.replace(text.find("nu = 0.22"), 9, "nu = 0.6");
  msg = catalogError(text);
  EXPECT_NE(msg.find(path_.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("glass"), std::string::npos) << msg;
}

// ------------------------------------------------------- the program

namespace {

class ProgramErrors : public ::testing::Test {
protected:
  void SetUp() override {
    ASSERT_EQ(run("add t1 --from-catalog table1-anisotropic").status, 0);
    ASSERT_EQ(run("add glass --from-catalog e-glass").status, 0);
    before_ = readFile(lib_);
    ASSERT_FALSE(before_.empty());
  }
  lamina::test::RunResult run(const std::string& args) { return runMaterials(dir_, lib_, args); }
  // Runs @p args, expects a non-zero exit, one line on stderr containing
  // every string of @p causes, and the library file unchanged.
  void expectFailure(const std::string& args, const std::vector<std::string>& causes) {
    const auto r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(lamina::test::lineCount(r.err), 1) << args << "\n" << r.err;
    for (const auto& c : causes)
      EXPECT_NE(r.err.find(c), std::string::npos) << args << ": '" << c << "' not in: " << r.err;
    EXPECT_EQ(readFile(lib_), before_) << args;
  }
  TempDir dir_;
  std::filesystem::path lib_ = dir_ / "library.toml";
  std::string before_;
};

// The 21 constants of a valid isotropic tensor (upper triangle row by row).
const std::string kIso =
    "2.8e11,1.2e11,1.2e11,0,0,0,2.8e11,1.2e11,0,0,0,2.8e11,0,0,0,8e10,0,0,8e10,0,8e10";

} // namespace

TEST_F(ProgramErrors, UnknownNameIsNamedWithTheEntries) {
  expectFailure("show nosuch", {"nosuch", "glass, t1"});
  expectFailure("show nosuch --json", {"nosuch"});
  expectFailure("export nosuch --format abaqus", {"nosuch"});
  expectFailure("remove nosuch", {"nosuch", "glass, t1"});
  expectFailure("layup stack --ply nosuch:0:1e-3", {"nosuch"});
  expectFailure("add x --from-catalog nosuch", {"nosuch", "catalog"});
}

TEST_F(ProgramErrors, WrongNumberOfConstants) {
  expectFailure("add x --constants 1,2,3 --density 1000", {"21", "got 3"});
  expectFailure("add x --constants " + kIso + ",1 --density 1000", {"21"});
  expectFailure("add x --constants " + kIso.substr(0, kIso.rfind(',')) + " --density 1000",
                {"21", "20"});
  expectFailure("add x --constants 2.8e11,abc" + kIso.substr(kIso.find(',', 7)) + " --density 1000",
                {"abc"});
}

TEST_F(ProgramErrors, NonPositiveDefiniteConstants) {
  std::string bad = kIso;
  bad.replace(0, 6, "-2.8e11");
  expectFailure("add neg --constants " + bad + " --density 1000", {"neg", "positive definite"});
}

TEST_F(ProgramErrors, BadDensity) {
  expectFailure("add x --constants " + kIso + " --density -5", {"density"});
  expectFailure("add x --constants " + kIso + " --density 0", {"density"});
  expectFailure("add x --constants " + kIso, {"density"});
}

TEST_F(ProgramErrors, DuplicateNameWritesNothing) {
  expectFailure("add t1 --from-catalog e-glass", {"t1", "already"});
}

TEST_F(ProgramErrors, BadPlies) {
  expectFailure("layup s --ply t1:0:0", {"thickness"});
  expectFailure("layup s --ply t1:0:-1e-3", {"thickness"});
  expectFailure("layup s --ply t1:zero:1e-3", {"zero"});
  expectFailure("layup s --ply t1", {"MATERIAL:ANGLE_DEG:THICKNESS_M"});
  // Beyond one turn either way (a fuzzer's 4.6e20 overflowed an int cast).
  expectFailure("layup s --ply t1:455555555555555555555:1e-3", {"angle", "360", "t1"});
  expectFailure("layup s --ply t1:-361:1e-3", {"angle", "-361"});
}

TEST_F(ProgramErrors, UnknownExportFormat) {
  expectFailure("export t1 --format nastran", {"nastran"});
}

TEST_F(ProgramErrors, MissingSubcommandIsAUsageError) {
  const auto r = run("");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lamina::test::lineCount(r.err), 1) << r.err;
}

// A library cut in the middle of an entry (an interrupted copy, a full disk
// in another tool) is malformed TOML: every command refuses it, naming the
// file and the line, and does not write.
TEST_F(ProgramErrors, TruncatedLibraryIsRefusedAndKept) {
  // Cut inside the C matrix of the second entry (an unterminated array).
  const std::size_t c = before_.find("C = [", before_.find("[materials.t1]"));
  ASSERT_NE(c, std::string::npos);
  const std::string cut = before_.substr(0, c + 40);
  writeFile(lib_, cut);
  before_ = cut;
  const std::string where = lib_.string() + ":";
  expectFailure("list", {where, "malformed TOML"});
  expectFailure("show t1", {where});
  expectFailure("add y --from-catalog aramid", {where});
  expectFailure("remove t1", {where});
}

// A TOML file that is not a lamina library is refused, named, and kept.
TEST_F(ProgramErrors, ForeignFileIsRefusedAndKept) {
  writeFile(lib_, "[package]\nname = \"something\"\nversion = \"1.0\"\n");
  before_ = readFile(lib_);
  expectFailure("list", {lib_.string(), "not a lamina materials library"});
  expectFailure("add y --from-catalog aramid", {lib_.string(), "not a lamina materials library"});
  writeFile(lib_, "[lamina]\nformat = \"csv\"\nversion = 1\n");
  before_ = readFile(lib_);
  expectFailure("add y --from-catalog aramid", {lib_.string(), "lamina.format"});
}
