// The law seam: one vocabulary of law names (the spellings the catalog, cell
// files and docs use), one 6x6 reader shared by every file, and linear
// elasticity behind the ConstitutiveLaw interface (sigma = C eps exactly,
// tangent C, no state).

#include "core/toml_reader.hpp"
#include "materials/law.hpp"
#include "materials/law_spec.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

namespace mat = lamina::materials;
namespace core = lamina::core;

TEST(LawSeam, OneSpellingPerLaw) {
  // the spellings documented in docs/materials.md and materials/catalog.toml
  const std::vector<std::pair<std::string, mat::LawKind>> names{
      {"isotropic", mat::LawKind::Isotropic},
      {"transversely-isotropic", mat::LawKind::TransverselyIsotropic},
      {"anisotropic", mat::LawKind::Anisotropic},
      {"gvbo", mat::LawKind::Gvbo}};
  for (const auto& [text, kind] : names) {
    ASSERT_TRUE(mat::kLawKindNames.parse(text).has_value()) << text;
    EXPECT_EQ(*mat::kLawKindNames.parse(text), kind);
    EXPECT_EQ(std::string(mat::toString(kind)), text);
    EXPECT_NE(mat::lawKindNames().find(text), std::string::npos);
  }
  EXPECT_FALSE(mat::kLawKindNames.parse("Isotropic").has_value()); // case matters: one spelling
  EXPECT_FALSE(mat::kLawKindNames.parse("iso").has_value());
  EXPECT_EQ(mat::lawKindNames().find("reduced-order"),
            std::string::npos); // given by an entry's name
}

TEST(LawSeam, ReadMatrix6NamesTheKey) {
  const toml::table doc =
      core::parseTomlString("C = [[1, 2], [3, 4]]\nD = [[1,0,0,0,0,0],[0,1,0,0,0,0],[0,0,1,0,0,0],"
                            "[0,0,0,1,0,0],[0,0,0,0,1,0],[0,0,0,0,0,7]]\n",
                            "m.toml");
  const core::TableReader t(doc, "m.toml");
  try {
    mat::readMatrix6(t, "C");
    FAIL() << "a 2x2 was accepted as a 6x6";
  } catch (const lamina::Error& e) {
    EXPECT_EQ(e.context().key, "C");
    EXPECT_NE(std::string(e.what()).find("6 rows of 6"), std::string::npos) << e.what();
  }
  const mat::Matrix6 d = mat::readMatrix6(t, "D");
  EXPECT_EQ(d(5, 5), 7.0);
  EXPECT_EQ(d(0, 0), 1.0);
  EXPECT_EQ(d(0, 5), 0.0);
}

TEST(LawSeam, LawSpecReadsEveryLinearLaw) {
  const toml::table doc = core::parseTomlString(
      "[a]\nlaw = \"isotropic\"\nE = 2e9\nnu = 0.25\n"
      "[b]\nlaw = \"transversely-isotropic\"\nE1 = 124e9\nE2 = 6.9e9\nG12 = 2.8e9\nnu12 = "
      "0.36\nnu23 = 0.46\n"
      "[c]\nlaw = \"rubber\"\n",
      "laws.toml");
  const core::TableReader root(doc, "laws.toml");
  const mat::LawSpec a = mat::readLawSpec(root.table("a"));
  EXPECT_EQ(a.kind, mat::LawKind::Isotropic);
  // isotropic: C11 = E (1 - nu) / ((1 + nu)(1 - 2 nu)) = 2e9 * 0.75 / (1.25 * 0.5) = 2.4e9
  EXPECT_NEAR(a.C(0, 0), 2.4e9, 1e-6 * 2.4e9);
  const mat::LawSpec b = mat::readLawSpec(root.table("b"));
  EXPECT_EQ(b.kind, mat::LawKind::TransverselyIsotropic);
  // the compliance of the engineering constants: S11 = 1/E1, S44 = 1/G12
  EXPECT_NEAR(b.C.compliance()(0, 0) * 124e9, 1.0, 1e-10);
  EXPECT_NEAR(b.C.compliance()(3, 3) * 2.8e9, 1.0, 1e-10);
  try {
    mat::readLawSpec(root.table("c"));
    FAIL() << "unknown law accepted";
  } catch (const lamina::Error& e) {
    EXPECT_EQ(e.context().key, "c.law");
    EXPECT_NE(std::string(e.what()).find("transversely-isotropic"), std::string::npos);
  }
}

TEST(LawSeam, LinearElasticLawIsSigmaEqualsCEps) {
  std::mt19937_64 rng(11);
  const mat::Stiffness C(lamina::test::randomSpd(rng));
  const mat::LinearElasticLaw law(mat::LawKind::Anisotropic, C);
  EXPECT_TRUE(law.isLinear());
  EXPECT_EQ(law.stateSize(), 0);
  mat::PointStep step;
  step.eps << 1e-3, -2e-3, 5e-4, 3e-3, -1e-3, 2e-3;
  step.dt = 1.0;
  mat::Vector6 sigma;
  mat::Matrix6 tangent;
  law.update(step, nullptr, nullptr, sigma, &tangent);
  const mat::Vector6 expect = C.matrix() * step.eps;
  // the same product: exact up to summation order
  EXPECT_LE((sigma - expect).norm(), 1e-14 * expect.norm());
  EXPECT_EQ(tangent, C.matrix());
  EXPECT_THROW(mat::LinearElasticLaw(mat::LawKind::Gvbo, C), lamina::Error);
}
