// Micro-inertia of a cell (GVBO chapter eqs. 38-39): exact zero for
// homogeneous cells, and the long-wave limit of the exact Floquet-Bloch
// relation of a periodic bilayer (Rytov) for waves normal to the layers.

#include "homogenize/dispersion.hpp"
#include "homogenize/homogenizer.hpp"
#include "micro/inclusion.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace lamina::test {
namespace {

using materials::Matrix6;
using materials::Stiffness;

/// Runs the six load cases of a cell and returns its dispersion.
homogenize::Dispersion dispersionOf(const homogenize::Grid& grid,
                                    const std::vector<std::int32_t>& map,
                                    const std::vector<Stiffness>& C,
                                    const std::vector<double>& density, double tol,
                                    homogenize::Result* result = nullptr) {
  homogenize::Options opt;
  opt.tol = tol;
  opt.threads = 1;
  homogenize::Homogenizer h(grid, map, C, density, opt);
  homogenize::DispersionAccumulator acc(grid, map, density);
  h.setDisplacementSink([&](int k, const double* u) { acc.addLoadCase(k, u); });
  const homogenize::Result r = h.run();
  if (result)
    *result = r;
  return acc.result();
}

homogenize::Grid gridOf(std::array<int, 3> n, Eigen::Vector3d size) {
  homogenize::Grid g;
  g.n = n;
  for (int d = 0; d < 3; ++d)
    g.h[static_cast<std::size_t>(d)] = size[d] / n[static_cast<std::size_t>(d)];
  return g;
}

// A cell of one material (two phases with the same law and density around a
// sphere) has no fluctuation at all: the right-hand side D^T C E of every
// load case is exactly zero, so H = 0, and Delta rho = 0 voxel by voxel, so
// h = 0 and D = 0, all bit for bit.
TEST(Dispersion, HomogeneousCellHasExactlyNone) {
  const std::array<int, 3> n{10, 8, 12};
  micro::Inclusion s;
  s.shape = micro::Shape::Sphere;
  s.phase = 1;
  s.semi.setConstant(0.3e-3);
  s.center = Eigen::Vector3d(0.5e-3, 0.5e-3, 0.5e-3);
  const auto map = micro::voxelize({s}, n, Eigen::Vector3d::Constant(1e-3));
  const Stiffness C = Stiffness::fromLame(2e9, 1e9);
  const auto d =
      dispersionOf(gridOf(n, Eigen::Vector3d::Constant(1e-3)), map, {C, C}, {1300.0, 1300.0}, 1e-8);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(d.H_rms[static_cast<std::size_t>(k)], 0.0) << k;
    EXPECT_EQ(d.residual[static_cast<std::size_t>(k)], 0.0) << k;
  }
  EXPECT_EQ(d.D.cwiseAbs().maxCoeff(), 0.0);
}

// ---- Rytov's exact relation for a periodic bilayer -----------------------
// Layers a (thickness d1, modulus M1, density r1) and b, period L = d1 + d2,
// waves normal to the layers (M: lambda + 2 mu for P waves, mu for S waves):
//   cos(k L) = cos(w a) cos(w b) - chi sin(w a) sin(w b),
//   a = d1/c1, b = d2/c2, chi = (Z1/Z2 + Z2/Z1)/2, Z = sqrt(M r), c = sqrt(M/r)
// (S. M. Rytov, Sov. Phys. Acoust. 2 (1956) 68). Expanding the right side to
// w^4, 1 - A w^2/2 + B w^4/24 with
//   A = a^2 + b^2 + 2 chi a b,  B = a^4 + 6 a^2 b^2 + b^4 + 4 chi a b (a^2 + b^2),
// and the left side to (kL)^4 gives w^2 = c^2 k^2 + g k^4 with
//   c^2 = L^2 / A,  g = L^4 (B/A^2 - 1) / (12 A).
// The micro-inertia model w^2 (rho + zeta^2 D k^2) = C k^2 expands to
// w^2 = (C/rho) k^2 - (C/rho)(zeta^2 D/rho) k^4, so the exact relation
// implies zeta^2 D = -g rho / c^2.
struct Bilayer {
  double d1, d2, M1, M2, r1, r2;
  double a() const { return d1 / std::sqrt(M1 / r1); }
  double b() const { return d2 / std::sqrt(M2 / r2); }
  double chi() const {
    const double z = std::sqrt(M1 * r1) / std::sqrt(M2 * r2);
    return 0.5 * (z + 1 / z);
  }
  double A() const { return a() * a() + b() * b() + 2 * chi() * a() * b(); }
  double B() const {
    const double a2 = a() * a(), b2 = b() * b();
    return a2 * a2 + 6 * a2 * b2 + b2 * b2 + 4 * chi() * a() * b() * (a2 + b2);
  }
  double L() const { return d1 + d2; }
  double c2() const { return L() * L() / A(); }
  double g() const { return std::pow(L(), 4) * (B() / (A() * A()) - 1) / (12 * A()); }
  double rho() const { return (d1 * r1 + d2 * r2) / L(); }
  double impliedDispersion() const { return -g() * rho() / c2(); }
  /// The exact acoustic-branch frequency at wavenumber k (bisection).
  double omega(double k) const {
    auto f = [&](double w) {
      return std::cos(w * a()) * std::cos(w * b()) - chi() * std::sin(w * a()) * std::sin(w * b()) -
             std::cos(k * L());
    };
    double lo = 0.5 * std::sqrt(c2()) * k, hi = 1.5 * std::sqrt(c2()) * k; // f(lo) > 0 > f(hi)
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (f(mid) > 0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
};

// The series above is algebra: check it against the exact root. At kL = 0.05
// the next term of w^2 is O((kL)^2) = 2.5e-3 of the k^4 term times an O(1)
// factor of the contrast, so 5 % bounds it with room.
TEST(Dispersion, RytovSeriesMatchesTheExactRoot) {
  const Bilayer b{0.3e-3, 0.7e-3, 200e9, 3e9, 7800, 1100};
  const double k = 0.05 / b.L(), w = b.omega(k);
  const double fourth = w * w - b.c2() * k * k;
  EXPECT_NEAR(fourth / (b.g() * k * k * k * k), 1.0, 0.05);
  EXPECT_LT(b.g(), 0); // long waves slow down in a laminate
}

/// One phase per voxel slab normal to @p axis: the first n1 slabs phase 0.
std::vector<std::int32_t> bilayerMap(const std::array<int, 3>& n, int axis, int n1) {
  std::vector<std::int32_t> map(static_cast<std::size_t>(n[0] * n[1] * n[2]));
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const int c = axis == 0 ? i : axis == 1 ? j : k;
        map[static_cast<std::size_t>((i * n[1] + j) * n[2] + k)] = c < n1 ? 0 : 1;
      }
  return map;
}

struct Contrast {
  double E2_over_E1, r2_over_r1;
  int n1; // voxels of layer 1 out of 16
};

// Waves normal to the layers: lamina's zeta^2 D for the P wave (the normal
// component) and the two S waves (the shear components containing the
// normal, lamina order) against the coefficient Rytov's relation implies,
// for contrasts in stiffness and in density. Whole-voxel layers make the
// rotated-grid H exact at the nodes and h piecewise linear, whose cell
// average the trilinear (here linear) mass symbol integrates exactly; what
// remains is the CG tolerance 1e-11 on H, amplified by the contrast (up to
// 300 here) in the quadratic form: 1e-9 relative bounds it (measured: 4e-15).
void checkBilayer(int axis) {
  static const int shear_of[3][2] = {{3, 5}, {3, 4}, {4, 5}}; // xy,xz | xy,yz | yz,xz
  const double L = 2e-3;
  const double E1 = 3e9, nu1 = 0.35, r1 = 1100, nu2 = 0.25;
  for (const Contrast& c : {Contrast{70.0, 7.1, 5}, Contrast{1.0, 8.0, 8}, Contrast{10.0, 1.0, 11},
                            Contrast{300.0, 0.2, 4}, Contrast{0.05, 3.0, 9}}) {
    std::array<int, 3> n{2, 2, 2};
    n[static_cast<std::size_t>(axis)] = 16;
    Eigen::Vector3d size = Eigen::Vector3d::Constant(L / 8);
    size[axis] = L;
    const double E2 = c.E2_over_E1 * E1, r2 = c.r2_over_r1 * r1;
    const Stiffness C1 = Stiffness::isotropic(E1, nu1), C2 = Stiffness::isotropic(E2, nu2);
    const auto d =
        dispersionOf(gridOf(n, size), bilayerMap(n, axis, c.n1), {C1, C2}, {r1, r2}, 1e-11);
    const double d1 = L * c.n1 / 16, d2 = L - d1;
    // P wave: constrained modulus lambda + 2 mu = C(axis, axis) of each phase
    const Bilayer P{d1, d2, C1(axis, axis), C2(axis, axis), r1, r2};
    const double DP = P.impliedDispersion();
    EXPECT_NEAR(d.D(axis, axis) / DP, 1.0, 1e-9)
        << "P, axis " << axis << ", E2/E1 " << c.E2_over_E1 << ", r2/r1 " << c.r2_over_r1;
    // S waves: shear modulus mu
    const Bilayer S{d1, d2, C1(3, 3), C2(3, 3), r1, r2};
    for (int s : shear_of[axis])
      EXPECT_NEAR(d.D(s, s) / S.impliedDispersion(), 1.0, 1e-9)
          << "S " << s << ", axis " << axis << ", E2/E1 " << c.E2_over_E1;
    // the density term of these three cases is a compatible strain (a
    // function of the normal coordinate along the normal): eq. 39 is solved
    // exactly; the in-plane normal cases are entirely incompatible (a
    // periodic h(x_n) has no in-plane normal strain)
    for (int k : {axis, shear_of[axis][0], shear_of[axis][1]})
      EXPECT_LT(d.residual[static_cast<std::size_t>(k)], 1e-12) << k;
    if (c.r2_over_r1 != 1.0)
      for (int k = 0; k < 3; ++k)
        if (k != axis) {
          EXPECT_NEAR(d.residual[static_cast<std::size_t>(k)], 1.0, 1e-12) << k;
        }
  }
}

TEST(Dispersion, BilayerNormalToXMatchesRytov) {
  checkBilayer(0);
}

TEST(Dispersion, BilayerNormalToZMatchesRytov) {
  checkBilayer(2);
}

// Equal impedances Z1 = Z2 make Rytov's relation non-dispersive
// (cos kL = cos w(a + b), chi = 1), and D_lin of the P wave vanishes: h' =
// E_h/E - rho/rho_bar is identically zero when E rho is the same in both
// layers. 1e-9 of the typical D of the cases above bounds the solver error.
TEST(Dispersion, EqualImpedanceLaminateIsNotDispersive) {
  const std::array<int, 3> n{16, 2, 2};
  const double L = 2e-3, E1 = 3e9, r1 = 1100;
  const Stiffness C1 = Stiffness::fromLame(E1, E1), C2 = Stiffness::fromLame(10 * E1, E1);
  const auto d = dispersionOf(gridOf(n, Eigen::Vector3d(L, L / 8, L / 8)), bilayerMap(n, 0, 6),
                              {C1, C2}, {r1, r1 / 4}, 1e-12);
  const double typical = r1 * L * L / 100; // rho L^2 / 100: the scale of D for strong contrast
  EXPECT_LT(std::abs(d.D(0, 0)), 1e-9 * typical);
  EXPECT_GT(d.D(3, 3), 1e-3 * typical); // the S waves see the contrast mu1 r1 != mu2 r2
}

// A centred sphere in a cube: the cell has cubic symmetry, and D must have
// it (the rotated stencil is symmetric under the cube's rotations, so to the
// CG tolerance 1e-10, amplified by the contrast 6: 1e-7 of max D). D is a
// Gram matrix: symmetric positive semi-definite. And it scales with the
// square of the cell size (zeta^2): a cell twice as large has 4 D.
TEST(Dispersion, SphereCellHasCubicSymmetryAndScalesWithSizeSquared) {
  const std::array<int, 3> n{12, 12, 12};
  micro::Inclusion s;
  s.shape = micro::Shape::Sphere;
  s.phase = 1;
  s.semi.setConstant(0.3);
  s.center = Eigen::Vector3d(0.5, 0.5, 0.5);
  const auto map = micro::voxelize({s}, n, Eigen::Vector3d::Ones());
  const std::vector<Stiffness> C{Stiffness::isotropic(156e6, 0.45), Stiffness::isotropic(1e9, 0.3)};
  const std::vector<double> rho{1100, 7800};
  const auto d1 = dispersionOf(gridOf(n, Eigen::Vector3d::Constant(1e-4)), map, C, rho, 1e-10);
  const auto d2 = dispersionOf(gridOf(n, Eigen::Vector3d::Constant(2e-4)), map, C, rho, 1e-10);
  const Matrix6& D = d1.D;
  const double m = D.cwiseAbs().maxCoeff(), tol = 1e-7 * m;
  ASSERT_GT(m, 0);
  EXPECT_NEAR(D(1, 1), D(0, 0), tol);
  EXPECT_NEAR(D(2, 2), D(0, 0), tol);
  EXPECT_NEAR(D(4, 4), D(3, 3), tol);
  EXPECT_NEAR(D(5, 5), D(3, 3), tol);
  EXPECT_NEAR(D(0, 2), D(0, 1), tol);
  EXPECT_NEAR(D(1, 2), D(0, 1), tol);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (i != j && (i >= 3 || j >= 3)) {
        EXPECT_NEAR(D(i, j), 0.0, tol) << i << "," << j;
      }
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Matrix6>(D).eigenvalues().minCoeff(), -tol);
  EXPECT_LT((d2.D - 4 * D).cwiseAbs().maxCoeff(), 1e-7 * 4 * m);
  // a sphere's density term is partly incompatible: the residual lies
  // strictly between 0 and 1
  EXPECT_GT(d1.residual[0], 0.01);
  EXPECT_LT(d1.residual[0], 0.99);
}

} // namespace
} // namespace lamina::test
