// A [[section]] holds the constitutive law its keys name: a catalog GVBO
// material is the chapter's GVBO law with Table 5, an inline law is the law
// of its keys, with exactly the stiffness of the E / C shortcuts, and a
// reduced-order library entry is its reduced-order cell.
#include "helpers.hpp"

#include "../core/test_util.hpp"
#include "../materials/reduced_order_cells.hpp"
#include "materials/gvbo_law.hpp"
#include "materials/stiffness.hpp"

#include <gtest/gtest.h>

using namespace lamina::membrane;
namespace mat = lamina::materials;

namespace {

/// The one section of a sheet built from @p keys on model @p model.
Section sectionOf(const std::string& keys, const std::string& model = "large_deflection") {
  return test::modelFromText(test::sectionSheet(keys, model)).sections.at(0);
}

/// The polyurea chapter's Table 5 in SI, written from the tables, not read
/// from any file: Table 11's soft domains (the reduced-order tests' cell)
/// have Table 5's rate parameters and their own E0, nu0; Table 5's are
/// 278 MPa and 0.491.
mat::GvboParameters table5() {
  mat::GvboParameters p = *lamina::test::softGvbo().gvbo;
  p.E0 = 278.0e6;
  p.nu0 = 0.491;
  return p;
}

/// Expects @p law to be a GvboLaw with the parameters of Table 5. Exact:
/// a decimal literal is parsed to the nearest double by TOML and C++ alike.
void expectTable5(const mat::LawPtr& law) {
  ASSERT_TRUE(law);
  ASSERT_EQ(law->kind(), mat::LawKind::Gvbo);
  const auto* gvbo = dynamic_cast<const mat::GvboLaw*>(law.get());
  ASSERT_NE(gvbo, nullptr);
  const mat::GvboParameters want = table5();
  EXPECT_EQ(gvbo->parameters().E0, want.E0);
  EXPECT_EQ(gvbo->parameters().nu0, want.nu0);
  for (const auto& [key, member] : mat::gvboTableKeys())
    EXPECT_EQ(gvbo->parameters().*member, want.*member) << key;
}

} // namespace

TEST(SectionLaw, CatalogGvboMaterialIsTheGvboLawOfTable5) {
  const Section s = sectionOf("material = \"polyurea-gvbo\"\n");
  expectTable5(s.law);
  EXPECT_FALSE(s.isLinear());
  EXPECT_EQ(s.material, "polyurea-gvbo (gvbo)");
  EXPECT_EQ(s.density, 1100.0); // Table 5: 1.1 g/cm^3
  // D is the instantaneous stiffness at rest, E0 and nu0 (eq. 15 at J = 1);
  // through Lame's constants it differs from the E, nu formula by round-off
  const mat::Matrix6 rest = mat::Stiffness::isotropic(278.0e6, 0.491).matrix();
  EXPECT_LT((s.D - rest).cwiseAbs().maxCoeff(), 1e-12 * rest.cwiseAbs().maxCoeff());
}

TEST(SectionLaw, InlineGvboLawIsTheCatalogsLaw) {
  const Section s = sectionOf(test::gvboTable5Keys());
  expectTable5(s.law);
  EXPECT_EQ(s.material, "inline gvbo");
  EXPECT_EQ(s.density, 1100.0);
}

TEST(SectionLaw, InlineIsotropicLawHasExactlyTheStiffnessOfEAndNu) {
  const std::string constants = "E = 2.5e9\nnu = 0.35\ndensity = 1200.0\n";
  for (const char* model : {"linear", "large_deflection"}) {
    const Section law = sectionOf("law = \"isotropic\"\n" + constants, model);
    const Section shortcut = sectionOf(constants, model);
    EXPECT_TRUE(law.D == shortcut.D) << model; // bit for bit
    ASSERT_TRUE(law.law && shortcut.law);
    EXPECT_EQ(law.law->kind(), mat::LawKind::Isotropic);
    EXPECT_EQ(shortcut.law->kind(), mat::LawKind::Isotropic);
    EXPECT_TRUE(law.isLinear());
    EXPECT_EQ(law.density, 1200.0);
  }
  // and that stiffness is Hooke's: lambda + 2G on the diagonal, G in shear
  const double E = 2.5e9, nu = 0.35, G = E / (2 * (1 + nu)),
               lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const Section s = sectionOf("law = \"isotropic\"\n" + constants);
  EXPECT_NEAR(s.D(0, 0), lambda + 2 * G, 1e-12 * E); // round-off of a few operations
  EXPECT_NEAR(s.D(0, 1), lambda, 1e-12 * E);
  EXPECT_NEAR(s.D(3, 3), G, 1e-12 * E);
}

TEST(SectionLaw, InlineAnisotropicLawHasExactlyTheGivenC) {
  const std::string C = "C = [[3.0e9, 1.0e9, 0.5e9, 0, 0, 0], [1.0e9, 2.0e9, 0.5e9, 0, 0, 0], "
                        "[0.5e9, 0.5e9, 1.5e9, 0, 0, 0], [0, 0, 0, 0.7e9, 0, 0], "
                        "[0, 0, 0, 0, 0.4e9, 0], [0, 0, 0, 0, 0, 0.6e9]]\ndensity = 1500.0\n";
  const Section law = sectionOf("law = \"anisotropic\"\n" + C, "linear");
  const Section shortcut = sectionOf(C, "linear");
  EXPECT_TRUE(law.D == shortcut.D);
  EXPECT_EQ(law.law->kind(), mat::LawKind::Anisotropic);
  EXPECT_EQ(law.D(0, 0), 3.0e9); // the entries as written
  EXPECT_EQ(law.D(1, 2), 0.5e9);
  EXPECT_EQ(law.D(5, 5), 0.6e9);
}

TEST(SectionLaw, InlineTransverselyIsotropicLawHasItsEngineeringConstants) {
  const Section s = sectionOf("law = \"transversely-isotropic\"\nE1 = 80e9\nE2 = 10e9\n"
                              "G12 = 5e9\nnu12 = 0.3\nnu23 = 0.4\ndensity = 1600.0\n",
                              "linear");
  EXPECT_EQ(s.law->kind(), mat::LawKind::TransverselyIsotropic);
  EXPECT_EQ(s.material, "inline transversely-isotropic");
  // the compliance D^-1 holds the constants: 1/E1, -nu12/E1, 1/G12 (axis x)
  const mat::Matrix6 S = s.D.inverse();
  EXPECT_NEAR(S(0, 0) * 80e9, 1.0, 1e-12); // round-off of a 6x6 inversion, twice
  EXPECT_NEAR(S(0, 1) * 80e9, -0.3, 1e-12);
  EXPECT_NEAR(S(1, 1) * 10e9, 1.0, 1e-12);
  EXPECT_NEAR(S(3, 3) * 5e9, 1.0, 1e-12);
}

TEST(SectionLaw, ReducedOrderEntryIsItsCell) {
  const lamina::test::TempDir dir;
  const mat::ReducedOrderModel cell = lamina::test::polyureaLaminate();
  lamina::test::addReducedOrderEntry(dir / "library.toml", "pu-cell", cell);
  const Model m =
      test::modelWithLibrary(test::sectionSheet("material = \"pu-cell\"\n"), dir / "library.toml");
  const Section& s = m.sections.at(0);
  ASSERT_TRUE(s.law);
  EXPECT_EQ(s.law->kind(), mat::LawKind::ReducedOrder);
  EXPECT_FALSE(s.isLinear());
  EXPECT_EQ(s.material, "pu-cell (reduced-order)");
  EXPECT_EQ(s.density, cell.density); // the entry's, as the library stored it
  // its state (reduced_order_law.hpp): 6 strains per partition (two layers)
  // and the GVBO state of the soft one; the elastic hard layer has none
  EXPECT_EQ(s.law->stateSize(), 6 * 2 + mat::GvboState::kSize);
}
