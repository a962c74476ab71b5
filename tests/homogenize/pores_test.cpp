// Pores (a phase with law = "void": zero stiffness) in the linear
// homogenization, against references outside the solver: the exact rank-1
// laminate with a void layer, the laminate formula's limit for a void ply,
// the Hashin-Shtrikman upper bound and the Voigt bound of a porous cell.
//
// With a void layer the laminate carries no traction across its layers: its
// C is the solid's in-plane (plane-stress) stiffness C_pp - C_pt C_tt^-1 C_tp
// times the solid fraction in the in-plane block and zero in every row and
// column that involves the normal (oracles.hpp's laminate() cannot take it:
// it inverts each layer's C_tt).

#include "oracles.hpp"

#include "homogenize/library_entry.hpp"
#include "micro/cell.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/unit_cell.hpp"

#include <string>

namespace lamina::test {
namespace {

/// The exact laminate of solid @p C (fraction @p fs) and void layers normal
/// to axis @p axis (0 = x, 1 = y, 2 = z).
Matrix6 voidLaminate(const Matrix6& C, double fs, int axis) {
  static const int t_of[3][3] = {{0, 3, 5}, {1, 3, 4}, {2, 4, 5}};
  std::array<int, 3> p{};
  int np = 0;
  for (int a = 0; a < 6; ++a)
    if (a != t_of[axis][0] && a != t_of[axis][1] && a != t_of[axis][2])
      p[static_cast<std::size_t>(np++)] = a;
  Eigen::Matrix3d tt, tp, pp;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      tt(a, b) = C(t_of[axis][a], t_of[axis][b]);
      tp(a, b) = C(t_of[axis][a], p[static_cast<std::size_t>(b)]);
      pp(a, b) = C(p[static_cast<std::size_t>(a)], p[static_cast<std::size_t>(b)]);
    }
  const Eigen::Matrix3d plane = pp - tp.transpose() * tt.inverse() * tp;
  Matrix6 out = Matrix6::Zero();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      out(p[static_cast<std::size_t>(a)], p[static_cast<std::size_t>(b)]) = fs * plane(a, b);
  return out;
}

// Layers of whole voxels, solid (a random anisotropic C) and void, normal to
// each axis: the rotated-grid solution is exact for a laminate (piecewise
// linear displacement across the layers), and the void layers make the
// system singular but consistent, so CG converges on its range. At tol
// 1e-10 the constants agree to ~1e-10 of max|C| (measured 1e-11 to 1e-12);
// 1e-8 as for the laminates of exact_test.cpp. The void layers are 3 and 4
// voxels thick: nodes inside them touch no solid voxel (free nodes).
TEST(Pores, VoidLaminateMatchesExactFormula) {
  std::mt19937 rng(29);
  const Stiffness solid = randomStiffness(rng);
  const Stiffness pore(Matrix6::Zero());
  for (int axis = 0; axis < 3; ++axis) {
    std::array<int, 3> n{4, 4, 4};
    n[static_cast<std::size_t>(axis)] = 12;
    std::vector<std::int32_t> map(static_cast<std::size_t>(n[0] * n[1] * n[2]), 0);
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) {
          const int c = axis == 0 ? i : axis == 1 ? j : k;
          // solid 0-2, void 3-6, solid 7-8, void 9-11: 5 of 12 solid
          map[static_cast<std::size_t>((i * n[1] + j) * n[2] + k)] =
              (c < 3 || (c >= 7 && c < 9)) ? 0 : 1;
        }
    const auto r = homogenizeMap(n, map, {solid, pore}, 1e-10, {1000.0, 0.0});
    const Matrix6 exact = voidLaminate(solid.matrix(), 5.0 / 12, axis);
    EXPECT_LT(relDiff(r.C.matrix(), exact), 1e-8) << "axis " << axis << "\n"
                                                  << r.C.matrix() << "\n\n"
                                                  << exact;
    EXPECT_NEAR(r.density, 1000.0 * 5 / 12, 1e-9);
    EXPECT_LT(r.maxResidual(), 1e-10);
  }
}

// The composite-voxel laminate of a solid and a void ply (C2 = 0) stays
// defined for a cut voxel (0 < c1 < 1): c2 K1 + c1 K2 = c2 K1 is invertible
// for c2 > 0, and the formula reduces to c1 (C1 - C1 B K1^-1 B^T C1).
// Along z it is the exact void laminate above (1e-12 relative: round-off of
// one 3x3 solve); for any normal n it has no stiffness against a strain
// sym(a (x) n) (the pore opens: C B(n) = 0 to round-off) and it is
// positive semi-definite.
TEST(Pores, LaminateFormulaWithVoidPly) {
  std::mt19937 rng(31);
  const Stiffness solid = randomStiffness(rng);
  const Stiffness pore(Matrix6::Zero());
  const double c1 = 0.37;
  const Matrix6 Cz = micro::laminateStiffness(solid, pore, c1, Eigen::Vector3d::UnitZ()).matrix();
  EXPECT_LT(relDiff(Cz, voidLaminate(solid.matrix(), c1, 2)), 1e-12);
  for (const Eigen::Vector3d& dir :
       {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(2, -1, 1), Eigen::Vector3d(0.3, 0.1, -0.9)}) {
    const Eigen::Vector3d n = dir.normalized();
    const Matrix6 C = micro::laminateStiffness(solid, pore, c1, n).matrix();
    const double scale = C.cwiseAbs().maxCoeff();
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d a = Eigen::Vector3d::Zero();
      a(c) = 1;
      const Eigen::Matrix3d e = 0.5 * (a * n.transpose() + n * a.transpose());
      materials::Vector6 v;
      v << e(0, 0), e(1, 1), e(2, 2), 2 * e(0, 1), 2 * e(1, 2), 2 * e(0, 2);
      EXPECT_LT((C * v).cwiseAbs().maxCoeff(), 1e-12 * scale) << n.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Matrix6> es(C);
    EXPECT_GE(es.eigenvalues().minCoeff(), -1e-12 * scale) << n.transpose();
    EXPECT_GT(es.eigenvalues()(3), 1e-3 * scale) << n.transpose(); // rank 3: the in-plane part
  }
}

micro::CellSpec cellFrom(const std::string& text) {
  return micro::readCellString(text, "pores.toml", micro::lazyCatalog());
}

// A void layer cut obliquely, normal [1, 1, 1], in a solid matrix: with
// composite voxels each cut voxel holds the exact laminate of its fraction
// with the void, and the cell is a laminate of laminates with one normal
// (as ObliqueLaminate.DiagonalNormalIsExactWithCompositeVoxels for two
// solids): the exact C to solver tolerance, 1e-8 of max|C| at tol 1e-9.
TEST(Pores, DiagonalVoidLayerIsExactWithCompositeVoxels) {
  const micro::CellSpec spec = cellFrom(
      "[cell]\nresolution = 16\n[[phases]]\nname = \"solid\"\nlaw = \"isotropic\"\nE = 10e9\n"
      "nu = 0.2\ndensity = 1000\n[[phases]]\nname = \"pore\"\nlaw = \"void\"\n[[inclusions]]\n"
      "phase = \"pore\"\nshape = \"layer\"\nnormal = [1, 1, 1]\nthickness = 0.15\n");
  // buildCell leaves a voxel cut by a pore whole: the laminates of the void
  // ply are formed here as they would be for two solids
  micro::UnitCell cell = micro::buildCell(spec);
  EXPECT_TRUE(cell.composites.empty());
  cell.composites =
      micro::findCompositeVoxels(cell.inclusions, cell.n, spec.size, cell.phase.values());
  ASSERT_FALSE(cell.composites.empty());
  homogenize::Options o;
  o.tol = 1e-9;
  const auto r = homogenize::homogenizeCell(spec, cell, "layer", 1.0, o).result;
  const Eigen::Vector3d n = cell.inclusions[0].unitDirection(cell.size);
  // the half-turn about (e_z + n) maps e_z to n (oblique_laminate_test.cpp)
  const Eigen::Vector3d m = (Eigen::Vector3d::UnitZ() + n).normalized();
  const Eigen::Matrix3d R = 2 * m * m.transpose() - Eigen::Matrix3d::Identity();
  const double fs = 1 - cell.analytic_fraction[0];
  const Matrix6 exact =
      Stiffness(voidLaminate(Stiffness::isotropic(10e9, 0.2).matrix(), fs, 2)).rotated(R).matrix();
  EXPECT_LT(relDiff(r.C.matrix(), exact), 1e-8) << r.C.matrix() << "\n\n" << exact;
}

std::string porousSphere(int N) {
  return "[cell]\nresolution = " + std::to_string(N) +
         "\n[[phases]]\nname = \"matrix\"\nlaw = \"isotropic\"\nE = 156e6\nnu = 0.494\n"
         "density = 1100\n[[phases]]\nname = \"pore\"\nlaw = \"void\"\n[[inclusions]]\n"
         "phase = \"pore\"\nshape = \"sphere\"\nradius = 0.3\nplacement = \"single\"\n"
         "volume_fraction = 0.19\n";
}

// The 19 % sphere cell with the sphere a pore at N = 16, 32, 48 (a voxel
// cut by a pore stays whole: staircase voxels, whose pore fraction 0.176,
// 0.188, 0.190 approaches 0.19 at these N): its bulk modulus (C11 +
// 2 C12)/3 (cubic symmetry) lies below the Hashin-Shtrikman upper bound for
// pores (the lower bound is 0: pores can disconnect the solid), C lies below
// the Voigt bound (1 - f) C_matrix, and C converges: the change from 32 to
// 48 is below the one from 16 to 32 for C11 and C44 (measured C11 320.6,
// 313.4, 313.3 MPa; C44 35.59, 34.91, 34.93 MPa). CG takes at most 60
// iterations per load case (measured 35 to 47 at tol 1e-7 for N = 16 to
// 32: staircase pores converge like a two-solid cell of moderate contrast).
// The staircase converges erratically with N (its pore fraction jumps):
// these three N approach 0.19 monotonically. About 9 s of CPU.
TEST(Pores, PorousSphereBelowHashinShtrikmanAndConverging) {
  const double E = 156e6, nu = 0.494;
  std::vector<Matrix6> C;
  for (int N : {16, 32, 48}) {
    const micro::CellSpec spec = cellFrom(porousSphere(N));
    const micro::UnitCell cell = micro::buildCell(spec);
    EXPECT_TRUE(cell.composites.empty()) << N;
    homogenize::Options o;
    o.tol = 1e-6;
    const auto r = homogenize::homogenizeCell(spec, cell, "porous", 1.0, o).result;
    C.push_back(r.C.matrix());
    const double f = cell.voxel_fraction[1]; // the pores' voxel fraction
    EXPECT_NEAR(f, 0.19, 0.015) << N;
    EXPECT_NEAR(r.density, (1 - f) * 1100, 1e-9 * 1100) << N;
    EXPECT_LT(r.maxResidual(), 1e-6) << N;
    for (int k = 0; k < 6; ++k)
      EXPECT_LT(r.cases[static_cast<std::size_t>(k)].iterations, 60) << N; // measured <= 35
    // phase 1 the pore (K = G = 0), phase 2 the matrix
    const auto hs = hashinShtrikman(0, 0, bulkOf(E, nu), shearOf(E, nu), 1 - f);
    const double K = (C.back()(0, 0) + 2 * C.back()(0, 1)) / 3;
    EXPECT_GT(K, 0) << N;
    EXPECT_LT(K, hs.K_hi) << N;
    const Matrix6 gap = (1 - f) * Stiffness::isotropic(E, nu).matrix() - C.back();
    Eigen::SelfAdjointEigenSolver<Matrix6> es(0.5 * (gap + gap.transpose()));
    EXPECT_GE(es.eigenvalues().minCoeff(), -1e-9 * C.back().cwiseAbs().maxCoeff()) << N;
  }
  for (const auto& [i, j] : {std::pair{0, 0}, std::pair{3, 3}}) {
    const double d1 = std::abs(C[1](i, j) - C[0](i, j)), d2 = std::abs(C[2](i, j) - C[1](i, j));
    EXPECT_LT(d2, d1) << "C" << i + 1 << j + 1 << ": " << C[0](i, j) << ", " << C[1](i, j) << ", "
                      << C[2](i, j);
  }
}

} // namespace
} // namespace lamina::test
