// The GVBO catalog entry against Table 5 of the polyurea chapter, and the
// deformation-dependent moduli against eqs. (13)-(16) with the chapter's
// rule that G, lambda and E never drop below their initial values.

#include "core/error.hpp"
#include "materials/catalog.hpp"
#include "materials/gvbo.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mat = lamina::materials;

namespace {

const mat::GvboParameters& polyurea() {
  static const mat::Catalog cat(lamina::test::catalogPath());
  return *cat.get("polyurea-gvbo").gvbo;
}

} // namespace

// Table 5 (MPa -> Pa): E0 = 278, nu0 = 0.491, Et = 23.3, p = -6, a2 = 10,
// k1 = 17, k2 = 0.47, k3 = 1.47, k4 = 4, Em = 13600, A0 = 1; density 1.1 g/cm^3.
TEST(Gvbo, PolyureaCatalogEntryMatchesTable5) {
  const mat::Catalog cat(lamina::test::catalogPath());
  const mat::CatalogEntry& e = cat.get("polyurea-gvbo");
  ASSERT_TRUE(e.gvbo.has_value());
  const mat::GvboParameters& g = *e.gvbo;
  EXPECT_EQ(g.E0, 278e6);
  EXPECT_EQ(g.nu0, 0.491);
  EXPECT_EQ(g.Et, 23.3e6);
  EXPECT_EQ(g.p, -6.0);
  EXPECT_EQ(g.a1, 0.0);
  EXPECT_EQ(g.a2, 10e6);
  EXPECT_EQ(g.k1, 17.0);
  EXPECT_EQ(g.k2, 0.47e6);
  EXPECT_EQ(g.k3, 1.47e6);
  EXPECT_EQ(g.k4, 4.0);
  EXPECT_EQ(g.Em, 13600e6);
  EXPECT_EQ(g.A0, 1e6);
  EXPECT_EQ(e.density, 1100.0);
  // The elastic stiffness of the entry is the J = 1 state: isotropic E0, nu0.
  EXPECT_EQ(e.C.matrix(), mat::Stiffness::isotropic(278e6, 0.491).matrix());
}

// J = 1: ln J = 0 and J^p = 1, so lambda = lambda0, G = G0 and eq. (16)
// gives back E0 and nu0 (a few roundings: 1e-14 relative).
TEST(Gvbo, UndeformedStateGivesInitialModuli) {
  const mat::GvboModuli m = mat::gvboModuli(polyurea(), 1.0);
  EXPECT_NEAR(m.E, 278e6, 1e-14 * 278e6);
  EXPECT_NEAR(m.nu, 0.491, 1e-14);
  EXPECT_NEAR(m.G, 278e6 / (2 * 1.491), 1e-14 * m.G);
}

// Compression J = 0.9 with p = -6 stiffens: lambda = J^p lambda0,
// G = J^p (G0 - lambda0 ln J), by hand from eqs. (13), (15), (16).
TEST(Gvbo, CompressionStiffensByEq13) {
  const double E0 = 278e6, nu0 = 0.491, J = 0.9;
  const double lambda0 = E0 * nu0 / ((1 + nu0) * (1 - 2 * nu0)), G0 = E0 / (2 * (1 + nu0));
  const double lambda = std::pow(J, -6.0) * lambda0;
  const double G = std::pow(J, -6.0) * (G0 - lambda0 * std::log(J));
  const mat::GvboModuli m = mat::gvboModuli(polyurea(), J);
  EXPECT_NEAR(m.lambda, lambda, 1e-14 * lambda);
  EXPECT_NEAR(m.G, G, 1e-14 * G);
  EXPECT_NEAR(m.E, G * (3 * lambda + 2 * G) / (lambda + G), 1e-14 * m.E);
  EXPECT_NEAR(m.nu, lambda / (2 * (lambda + G)), 1e-14);
  EXPECT_GT(m.E, E0);
}

// Expansion J = 1.1: eq. (13) would lower both Lame constants (J^-6 < 1 and
// ln J > 0), so the initial values are kept: E = E0, nu = nu0.
TEST(Gvbo, ExpansionKeepsInitialModuli) {
  const mat::GvboModuli m = mat::gvboModuli(polyurea(), 1.1);
  EXPECT_NEAR(m.E, 278e6, 1e-14 * 278e6);
  EXPECT_NEAR(m.nu, 0.491, 1e-14);
}

TEST(Gvbo, RejectsNonPositiveJ) {
  EXPECT_THROW(mat::gvboModuli(polyurea(), 0.0), lamina::Error);
  EXPECT_THROW(mat::gvboModuli(polyurea(), -1.0), lamina::Error);
  EXPECT_THROW(mat::gvboModuli(polyurea(), std::nan("")), lamina::Error);
}
