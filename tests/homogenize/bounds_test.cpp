// Spheres in a matrix against the bounds and estimates of isotropic
// micromechanics: Hashin-Shtrikman, dilute Eshelby, Voigt/Reuss; cubic
// symmetry of a simple cubic array.

#include "oracles.hpp"

#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

namespace lamina::test {
namespace {

// Table 11 moduli of the polyurea chapter (soft matrix, hard domains).
const double E1 = 156e6, nu1 = 0.494, E2 = 890e6, nu2 = 0.491;

micro::CellSpec cellFrom(const std::string& text) {
  return micro::readCellString(text, "test-cell", micro::lazyCatalog());
}

std::string twoPhaseCell(int N, const std::string& inclusions) {
  return "[cell]\nresolution = " + std::to_string(N) +
         "\n[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 156e6\nnu = 0.494\ndensity = "
         "1000\n[[phases]]\nname = \"i\"\nlaw = \"isotropic\"\nE = 890e6\nnu = 0.491\ndensity = "
         "3000\n[[inclusions]]\nphase = \"i\"\n" +
         inclusions;
}

struct Solved {
  micro::UnitCell cell;
  homogenize::Result r;
  std::vector<Stiffness> C;
};

Solved solve(const std::string& text, double tol) {
  const micro::CellSpec spec = cellFrom(text);
  Solved s{micro::buildCell(spec), {}, spec.stiffnessesAt(1.0)};
  s.r = homogenizeUnitCell(s.cell, s.C, tol, spec.densities());
  return s;
}

// One centred sphere = simple cubic array. The voxel set is invariant under
// the 48 symmetries of the cube, so C is cubic to round-off and solver
// tolerance (1e-9 relative at tol 1e-10). Its bulk modulus (C11 + 2 C12)/3
// lies in the Hashin-Shtrikman window (a bound for any isotropic-phase
// geometry with this fraction, here the voxel fraction reached); the density
// is the volume average.
TEST(SingleSphere, CubicSymmetryAndBulkInsideHashinShtrikman) {
  const auto s =
      solve(twoPhaseCell(24, "shape = \"sphere\"\nradius = 0.3\nvolume_fraction = 0.19\n"), 1e-10);
  const Matrix6& C = s.r.C.matrix();
  const double scale = C.cwiseAbs().maxCoeff();
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(C(a, a), C(0, 0), 1e-9 * scale);
    EXPECT_NEAR(C(3 + a, 3 + a), C(3, 3), 1e-9 * scale);
    for (int b = 0; b < 3; ++b)
      if (a != b) {
        EXPECT_NEAR(C(a, b), C(0, 1), 1e-9 * scale);
      }
  }
  for (int a = 0; a < 6; ++a)
    for (int b = 3; b < 6; ++b)
      if (a != b) {
        EXPECT_NEAR(C(a, b), 0.0, 1e-9 * scale);
      }
  EXPECT_EQ(s.r.symmetry.cls, materials::SymmetryClass::Cubic);
  const double f = s.cell.voxel_fraction[1];
  const auto hs =
      hashinShtrikman(bulkOf(E1, nu1), shearOf(E1, nu1), bulkOf(E2, nu2), shearOf(E2, nu2), f);
  const double K = (C(0, 0) + 2 * C(0, 1)) / 3;
  EXPECT_GT(K, hs.K_lo);
  EXPECT_LT(K, hs.K_hi);
  EXPECT_NEAR(s.r.density, (1 - f) * 1000 + f * 3000, 1e-9);
  expectWithinVoigtReuss(C, s.C, s.cell.voxel_fraction);
}

// Many random non-overlapping spheres: statistically isotropic. For 40
// spheres at 20 % in 40^3 voxels the sample anisotropy is a few per cent:
// we require the moduli along x, y, z to agree within 3 %, the cubic
// anisotropy ratio 2 C44 / (C11 - C12) to be 1 within 5 %, and the
// isotropic projections K and G to lie inside the Hashin-Shtrikman bounds.
TEST(RandomSpheres, IsotropicWithinToleranceAndInsideHashinShtrikman) {
  const auto s = solve(twoPhaseCell(40, "shape = \"sphere\"\nradius = 0.1\nplacement = "
                                        "\"random\"\ncount = 40\nvolume_fraction = 0.2\nseed = "
                                        "4\nmin_gap = 0.02\n"),
                       1e-6);
  const Matrix6& C = s.r.C.matrix();
  const double c11 = (C(0, 0) + C(1, 1) + C(2, 2)) / 3, c44 = (C(3, 3) + C(4, 4) + C(5, 5)) / 3;
  const double c12 = (C(0, 1) + C(1, 2) + C(0, 2)) / 3;
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(C(a, a) / c11, 1.0, 0.03);
    EXPECT_NEAR(C(3 + a, 3 + a) / c44, 1.0, 0.03);
  }
  EXPECT_NEAR(2 * c44 / (c11 - c12), 1.0, 0.05);
  const double f = s.cell.voxel_fraction[1];
  const auto hs =
      hashinShtrikman(bulkOf(E1, nu1), shearOf(E1, nu1), bulkOf(E2, nu2), shearOf(E2, nu2), f);
  const double K = materials::voigtBulk(s.r.C), G = materials::voigtShear(s.r.C);
  EXPECT_GT(K, hs.K_lo);
  EXPECT_LT(K, hs.K_hi);
  EXPECT_GT(G, hs.G_lo);
  EXPECT_LT(G, hs.G_hi);
  expectWithinVoigtReuss(C, s.C, s.cell.voxel_fraction);
}

// A dilute sphere (2 %): the change of the moduli per unit fraction is the
// dilute Eshelby estimate (Eshelby 1957; e.g. Qu & Cherkaoui eqs. 6.15):
//   dK/df = (K2 - K1)(3 K1 + 4 G1)/(3 K2 + 4 G1),
//   dG/df = (G2 - G1) / (1 + beta1 (G2 - G1)/G1), beta1 = 2(4 - 5 nu1)/(15(1 - nu1)).
// Interaction in the cubic array (O(f)) and the staircase surface at 32^3
// (radius 5.4 voxels) each change it by a few per cent: 10 % tolerance.
TEST(DiluteSphere, CloseToEshelbyEstimate) {
  const double Ea = 1e9, nua = 0.3, Eb = 3e9, nub = 0.3;
  const std::string text =
      "[cell]\nresolution = 32\n[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 1e9\nnu = "
      "0.3\ndensity = 1000\n[[phases]]\nname = \"i\"\nlaw = \"isotropic\"\nE = 3e9\nnu = "
      "0.3\ndensity = 1000\n[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\nradius = "
      "0.1\nvolume_fraction = 0.02\n";
  const auto s = solve(text, 1e-8);
  const double f = s.cell.voxel_fraction[1];
  const double K1 = bulkOf(Ea, nua), G1 = shearOf(Ea, nua), K2 = bulkOf(Eb, nub),
               G2 = shearOf(Eb, nub);
  const double dK = (K2 - K1) * (3 * K1 + 4 * G1) / (3 * K2 + 4 * G1);
  const double beta = 2 * (4 - 5 * nua) / (15 * (1 - nua));
  const double dG = (G2 - G1) / (1 + beta * (G2 - G1) / G1);
  const double K = materials::voigtBulk(s.r.C), G = materials::voigtShear(s.r.C);
  EXPECT_NEAR((K - K1) / f / dK, 1.0, 0.10);
  EXPECT_NEAR((G - G1) / f / dG, 1.0, 0.10);
  expectWithinVoigtReuss(s.r.C.matrix(), s.C, s.cell.voxel_fraction);
}

} // namespace
} // namespace lamina::test
