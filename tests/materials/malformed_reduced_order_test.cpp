/// @file malformed_reduced_order_test.cpp
/// @brief Reduced-order entries under bad input: a missing or changed side
/// file, an entry without phases, side file or checksum, `law =
/// "reduced-order"` where a law with keys is expected, a Newton that does
/// not converge, and the reduced-order options of `materials drive` on
/// another law; every error names the entry, the file, the key or the
/// option, and nothing is written.

#include "reduced_order_cells.hpp"

#include "core/toml_reader.hpp"
#include "materials/catalog.hpp"
#include "materials/material_source.hpp"
#include "materials/reduced_order_law.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace lamina {
namespace {

namespace mat = materials;
using test::errorOf;

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class MalformedReducedOrder : public ::testing::Test {
protected:
  void SetUp() override {
    test::addReducedOrderEntry(lib_, "polyurea-cell", test::polyureaLaminate());
  }
  test::RunResult run(const std::string& args) { return test::runMaterials(dir_, lib_, args); }
  std::filesystem::path sideFile() const {
    const mat::Library lib(lib_);
    return lib.folder() / lib.get("polyurea-cell").side_file;
  }
  /// `materials drive polyurea-cell` (confined, 1e3 /s) to out.csv with @p extra.
  test::RunResult drive(const std::string& extra = "") {
    return run("drive polyurea-cell --path confined --rate 1e3 --to 0.3 --steps 3 --out '" +
               out_.string() + "' " + extra);
  }
  test::TempDir dir_;
  std::filesystem::path lib_ = dir_.path() / "library.toml", out_ = dir_.path() / "out.csv";
};

TEST_F(MalformedReducedOrder, MissingSideFileNamesEntryAndFile) {
  const auto side = sideFile();
  std::filesystem::remove(side);
  const std::string e = errorOf([&] { mat::MaterialSource(lib_.string()).law("polyurea-cell"); });
  EXPECT_TRUE(has(e, "'polyurea-cell'") && has(e, side.string()) && has(e, "missing")) << e;
  const auto r = drive();
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(has(r.err, "'polyurea-cell'") && has(r.err, side.string())) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out_)) << "nothing written";
}

TEST_F(MalformedReducedOrder, SideFileChangedAfterWritingIsRefused) {
  const auto side = sideFile();
  std::ofstream(side, std::ios::app) << 'x'; // one byte more
  const auto r = drive();
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(has(r.err, "'polyurea-cell'") && has(r.err, side.string()) &&
              has(r.err, "checksum") && has(r.err, "changed"))
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(out_));
  EXPECT_EQ(run("show polyurea-cell").status, 1) << "show reads the side file too";
}

/// The library text of the entry with the part from @p from up to @p to removed.
std::string without(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t a = text.find(from), b = text.find(to, a);
  EXPECT_NE(a, std::string::npos) << from;
  EXPECT_NE(b, std::string::npos) << to;
  return text.substr(0, a) + text.substr(b);
}

TEST_F(MalformedReducedOrder, EntryWithoutPhasesSideFileOrChecksumNamesTheKey) {
  const std::string text = test::readFile(lib_);
  const auto parse = [](const std::string& t) {
    return errorOf([&] { mat::Library::parse(t, "lib.toml"); });
  };
  std::string e = parse(without(text, "\n[[materials.polyurea-cell.phases]]",
                                "\n[materials.polyurea-cell.provenance]"));
  EXPECT_TRUE(has(e, "lib.toml:") && has(e, "materials.polyurea-cell.phases") &&
              has(e, "at least one phase"))
      << e;
  e = parse(without(text, "side_checksum = ", "C = ["));
  EXPECT_TRUE(has(e, "materials.polyurea-cell.side_checksum") && has(e, "checksum")) << e;
  e = parse(without(text, "side_file = ", "side_checksum"));
  EXPECT_TRUE(has(e, "materials.polyurea-cell.side_file") && has(e, "side file")) << e;
  // a phase's law is a law with keys, never a reduced-order cell
  std::string nested = text;
  nested.replace(nested.find("law = \"gvbo\""), 12, "law = \"reduced-order\"");
  e = parse(nested);
  EXPECT_TRUE(has(e, "phases") && has(e, "law") && has(e, "library entry")) << e;
  // and an entry added without its side file is refused before anything is written
  mat::Material m = test::reducedOrderEntry("no-side", test::polyureaLaminate());
  e = errorOf([&] { mat::Library(lib_).add(m); });
  EXPECT_TRUE(has(e, "no-side") && has(e, "side file")) << e;
  EXPECT_EQ(test::readFile(lib_), text);
}

TEST_F(MalformedReducedOrder, ReducedOrderIsNotALawWithKeys) {
  // a catalog entry
  const auto catalog = dir_.path() / "catalog.toml";
  test::writeFile(catalog, "[cell]\ndescription = \"x\"\nsource = \"y\"\ndensity = 1000.0\n"
                           "law = \"reduced-order\"\n");
  std::string e = errorOf([&] { mat::Catalog{catalog}; });
  EXPECT_TRUE(has(e, catalog.string()) && has(e, "cell.law") &&
              has(e, "homogenize --reduced-order"))
      << e;
  // a cell file's phase (read by micro::readPhase through readLawSpec)
  const toml::table doc = core::parseTomlString(
      "[[phases]]\nname = \"soft\"\nlaw = \"reduced-order\"\ndensity = 1100.0\n", "cell.toml");
  const core::TableReader root(doc, "cell.toml");
  e = errorOf([&] { mat::readLawSpec(root.tableArray("phases")[0]); });
  EXPECT_TRUE(has(e, "cell.toml") && has(e, "phases[0].law") && has(e, "referred to by its name"))
      << e;
  // and no law object of that kind is made from a spec
  mat::LawSpec spec;
  spec.kind = mat::LawKind::ReducedOrder;
  EXPECT_THROW(spec.make(), Error);
}

TEST_F(MalformedReducedOrder, NewtonThatDoesNotConvergeNamesEntryStepAndResidual) {
  const auto r = drive("--newton-iterations 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(has(r.err, "'polyurea-cell'") && has(r.err, "step 1 of 3") && has(r.err, "t = ") &&
              has(r.err, "residual") && has(r.err, "after 1 iterations"))
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(out_));
  EXPECT_EQ(drive("--newton-iterations 0").status, 2) << "a cap below 1 is a usage error";
}

TEST_F(MalformedReducedOrder, ReducedOrderOptionsOnAnotherLawAreRefused) {
  const auto d = dir_.path() / "d.csv";
  for (const std::string& opt :
       {"--nonlinear-dispersion '" + d.string() + "'", std::string("--newton-iterations 5"),
        std::string("--newton-tolerance 1e-8")}) {
    const auto r = run("drive polyurea-gvbo --path shear --rate 1 --to 0.1 --out '" +
                       out_.string() + "' " + opt);
    EXPECT_EQ(r.status, 1) << opt;
    EXPECT_TRUE(has(r.err, opt.substr(0, opt.find(' '))) && has(r.err, "reduced-order entries") &&
                has(r.err, "gvbo"))
        << r.err;
  }
  auto r = drive("--nonlinear-dispersion '" + out_.string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(has(r.err, "--nonlinear-dispersion") && has(r.err, "--out")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out_));
  r = run("export polyurea-cell --format abaqus");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(has(r.err, "--format") && has(r.err, "reduced-order") && has(r.err, "json")) << r.err;
}

} // namespace
} // namespace lamina

namespace lamina {
namespace {

// The phases live in the library text, outside the side file's checksum:
// swapping them (or editing a modulus) must not give a law whose L0 no
// longer belongs to A and P. The law checks sum c L0 A against the side
// file's C (1e-9 of max|C|; the swap changes it by tens of per cent).
TEST(MalformedReducedOrderPhases, PhasesThatDoNotMatchTheArraysAreRefused) {
  materials::ReducedOrderModel m = test::polyureaLaminate();
  std::swap(m.phases[0].law, m.phases[1].law);
  const std::string e = test::errorOf([&] { materials::ReducedOrderLaw("swapped", m); });
  EXPECT_NE(e.find("'swapped'"), std::string::npos) << e;
  EXPECT_NE(e.find("do not match the side file"), std::string::npos) << e;
}

// A membrane section or a layup ply naming a reduced-order entry would use
// its C alone and drop the law: refused, naming the entry.
TEST(MalformedReducedOrderPhases, LayupOfAReducedOrderEntryIsRefused) {
  test::TempDir dir;
  const auto lib = dir.path() / "library.toml";
  test::addReducedOrderEntry(lib, "pu-cell", test::polyureaLaminate());
  const test::RunResult r = test::runMaterials(dir, lib, "layup lay --ply pu-cell:0:0.001");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("'pu-cell' is a reduced-order cell"), std::string::npos) << r.err;
}

} // namespace
} // namespace lamina
