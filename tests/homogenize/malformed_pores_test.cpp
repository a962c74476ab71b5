// Void phases (pores) where they make no sense are refused with a clear
// error naming the file and key: elastic constants or a density on a void
// phase, a cell that is all void, `law = "void"` outside a cell's phases
// (catalog entries, case sections), nonlinear runs (--path,
// --tangent-rates), reduced-order cells and the dispersion tensor of a
// cell with a size; and a stiffness list without a positive definite one.

#include "core/error.hpp"
#include "core/toml_reader.hpp"
#include "homogenize/homogenizer.hpp"
#include "homogenize/library_entry.hpp"
#include "homogenize/nonlinear_run.hpp"
#include "homogenize/reduced_order_run.hpp"
#include "materials/law_spec.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lamina::test {
namespace {

const std::string kSolid = "[cell]\nresolution = 8\n[[phases]]\nname = \"m\"\nlaw = "
                           "\"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n";
const std::string kPore = "[[phases]]\nname = \"pore\"\nlaw = \"void\"\n";
const std::string kSphere =
    "[[inclusions]]\nphase = \"pore\"\nshape = \"sphere\"\nradius = 0.3\nplacement = \"single\"\n";

template <class F>
std::string errorOf(F&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

micro::CellSpec cellFrom(const std::string& text) {
  return micro::readCellString(text, "pores.toml", micro::lazyCatalog());
}

TEST(MalformedPores, VoidPhaseHasNoConstantsNorDensity) {
  std::string e = errorOf([] { cellFrom(kSolid + kPore + "E = 1e6\n" + kSphere); });
  EXPECT_TRUE(has(e, "pores.toml") && has(e, "phases[1].E") && has(e, "zero stiffness")) << e;
  e = errorOf([] { cellFrom(kSolid + kPore + "C = [[1.0]]\n" + kSphere); });
  EXPECT_TRUE(has(e, "phases[1].C") && has(e, "no elastic constants")) << e;
  e = errorOf([] { cellFrom(kSolid + kPore + "density = 0\n" + kSphere); });
  EXPECT_TRUE(has(e, "phases[1].density") && has(e, "zero density")) << e;
  e = errorOf([] { cellFrom(kSolid + kPore + "J = 1.1\n" + kSphere); });
  EXPECT_TRUE(has(e, "phases[1].J") && has(e, "gvbo phases only")) << e;
  // an unknown law in a cell names 'void' among the choices
  e = errorOf([] { cellFrom(kSolid + "[[phases]]\nname = \"pore\"\nlaw = \"vacuum\"\n" + kSphere); });
  EXPECT_TRUE(has(e, "phases[1].law") && has(e, "'vacuum'") && has(e, "'void' for a pore")) << e;
  // E = 0 points to the void law
  e = errorOf([] {
    cellFrom(kSolid + "[[phases]]\nname = \"pore\"\nlaw = \"isotropic\"\nE = 0\nnu = 0.3\n"
                      "density = 1\n" + kSphere);
  });
  EXPECT_TRUE(has(e, "phases[1].E") && has(e, "must be positive") && has(e, "law = \"void\""))
      << e;
  // a well-formed void phase reads: zero stiffness and density
  const micro::CellSpec spec = cellFrom(kSolid + kPore + kSphere);
  EXPECT_TRUE(spec.phases[1].isVoid());
  EXPECT_EQ(spec.phases[1].density, 0.0);
  EXPECT_TRUE(spec.phases[1].C.matrix().isZero(0.0));
}

TEST(MalformedPores, AllVoidCellIsRefused) {
  std::string e = errorOf([] { cellFrom("[cell]\nresolution = 8\n" + kPore); });
  EXPECT_TRUE(has(e, "pores.toml") && has(e, "phases") && has(e, "every phase is void")) << e;
  // the homogenizer itself, given only zero stiffnesses
  homogenize::Grid g;
  g.n = {4, 4, 4};
  g.h = {0.25, 0.25, 0.25};
  e = errorOf([&] {
    homogenize::Homogenizer h(g, std::vector<std::int32_t>(64, 0),
                              {materials::Stiffness(materials::Matrix6::Zero())}, {0.0}, {});
    h.run();
  });
  EXPECT_TRUE(has(e, "all void")) << e;
}

TEST(MalformedPores, VoidOnlyInACellsPhases) {
  // a catalog entry or a case section reads its law with VoidLaw::Refused
  const toml::table doc = core::parseTomlString("[a]\nlaw = \"void\"\n", "catalog.toml");
  const core::TableReader root(doc, "catalog.toml");
  const std::string e = errorOf([&] { materials::readLawSpec(root.table("a")); });
  EXPECT_TRUE(has(e, "catalog.toml") && has(e, "a.law") && has(e, "only a cell's [[phases]]"))
      << e;
}

TEST(MalformedPores, NonlinearReducedOrderAndDispersionAreRefused) {
  const micro::CellSpec spec = cellFrom(kSolid + kPore + kSphere);
  std::string e = errorOf([&] { homogenize::phaseLaws(spec); });
  EXPECT_TRUE(has(e, "pores.toml") && has(e, "'pore' is void") && has(e, "--path") &&
              has(e, "--tangent-rates"))
      << e;
  const micro::UnitCell cell = micro::buildCell(spec);
  e = errorOf([&] { homogenize::checkReducible(spec, cell); });
  EXPECT_TRUE(has(e, "pores.toml") && has(e, "'pore' is void") && has(e, "reduced-order")) << e;
  // with a size the entry would get the dispersion tensor
  const std::string sized = "[cell]\nresolution = 8\nsize = 1e-4\n" + kSolid.substr(22);
  const micro::CellSpec spec_sized = cellFrom(sized + kPore + "[[inclusions]]\nphase = "
                                                               "\"pore\"\nshape = \"sphere\"\n"
                                                               "radius = 3e-5\n");
  e = errorOf([&] {
    homogenize::homogenizeCell(spec_sized, micro::buildCell(spec_sized), "x", 1.0, {});
  });
  EXPECT_TRUE(has(e, "pores.toml") && has(e, "cell.size") && has(e, "dispersion")) << e;
}

} // namespace
} // namespace lamina::test
