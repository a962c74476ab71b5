#pragma once
// Independent reference results for the homogenizer tests: exact laminate
// formula, Hashin-Shtrikman bounds, dilute Eshelby estimate, Voigt/Reuss
// bounds. None of this calls lamina::homogenize.

#include "homogenize/grid.hpp"
#include "homogenize/homogenizer.hpp"
#include "materials/stiffness.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

namespace lamina::test {

using materials::Matrix6;
using materials::Stiffness;

/// Exact effective stiffness of a laminate with layers normal to @p axis
/// (0=x, 1=y, 2=z), layer stiffness C[k] and fraction f[k]. Continuous across
/// the layers: the traction components (t: those involving the normal) of
/// stress and the in-plane (p) components of strain. With sigma_t, eps_p as
/// unknowns: C_tt* = <C_tt^-1>^-1, C_tp* = C_tt* <C_tt^-1 C_tp>,
/// C_pp* = <C_pp - C_pt C_tt^-1 C_tp> + <C_pt C_tt^-1> C_tt* <C_tt^-1 C_tp>.
inline Matrix6 laminate(const std::vector<Matrix6>& C, const std::vector<double>& f, int axis) {
  // lamina order [xx, yy, zz, xy, yz, xz]: components that contain the normal
  static const int t_of[3][3] = {{0, 3, 5}, {1, 3, 4}, {2, 4, 5}};
  std::array<int, 3> t{}, p{};
  int np = 0;
  for (int a = 0; a < 3; ++a)
    t[static_cast<std::size_t>(a)] = t_of[axis][a];
  for (int a = 0; a < 6; ++a)
    if (a != t[0] && a != t[1] && a != t[2])
      p[static_cast<std::size_t>(np++)] = a;
  using M3 = Eigen::Matrix3d;
  M3 inv_tt = M3::Zero(), inv_tt_tp = M3::Zero(), pt_inv_tt = M3::Zero(), schur = M3::Zero();
  for (std::size_t k = 0; k < C.size(); ++k) {
    M3 tt, tp, pt, pp;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        tt(a, b) = C[k](t[a], t[b]);
        tp(a, b) = C[k](t[a], p[b]);
        pt(a, b) = C[k](p[a], t[b]);
        pp(a, b) = C[k](p[a], p[b]);
      }
    const M3 itt = tt.inverse();
    inv_tt += f[k] * itt;
    inv_tt_tp += f[k] * itt * tp;
    pt_inv_tt += f[k] * pt * itt;
    schur += f[k] * (pp - pt * itt * tp);
  }
  const M3 Ctt = inv_tt.inverse();
  const M3 Ctp = Ctt * inv_tt_tp;
  const M3 Cpt = pt_inv_tt * Ctt;
  const M3 Cpp = schur + pt_inv_tt * Ctt * inv_tt_tp;
  Matrix6 out;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      out(t[a], t[b]) = Ctt(a, b);
      out(t[a], p[b]) = Ctp(a, b);
      out(p[a], t[b]) = Cpt(a, b);
      out(p[a], p[b]) = Cpp(a, b);
    }
  return out;
}

/// Hashin-Shtrikman bounds of a two-phase isotropic composite (well-ordered
/// phases: phase 1 softer in both K and G). Hashin & Shtrikman, J. Mech.
/// Phys. Solids 11 (1963) 127.
struct HsBounds {
  double K_lo, K_hi, G_lo, G_hi;
};
inline HsBounds hashinShtrikman(double K1, double G1, double K2, double G2, double f2) {
  const double f1 = 1 - f2;
  HsBounds b;
  b.K_lo = K1 + f2 / (1 / (K2 - K1) + 3 * f1 / (3 * K1 + 4 * G1));
  b.K_hi = K2 + f1 / (1 / (K1 - K2) + 3 * f2 / (3 * K2 + 4 * G2));
  b.G_lo = G1 + f2 / (1 / (G2 - G1) + 6 * f1 * (K1 + 2 * G1) / (5 * G1 * (3 * K1 + 4 * G1)));
  b.G_hi = G2 + f1 / (1 / (G1 - G2) + 6 * f2 * (K2 + 2 * G2) / (5 * G2 * (3 * K2 + 4 * G2)));
  return b;
}

/// Bulk and shear moduli from E and nu.
inline double bulkOf(double E, double nu) {
  return E / (3 * (1 - 2 * nu));
}
inline double shearOf(double E, double nu) {
  return E / (2 * (1 + nu));
}

/// Asserts Reuss <= C <= Voigt in the sense of quadratic forms (eigenvalues
/// of C_V - C and C - C_R not below -rel * max|C|): the discrete cell problem
/// is a minimum of energy over compatible strains (upper, Voigt) and of
/// complementary energy over equilibrated stresses (lower, Reuss).
inline void expectWithinVoigtReuss(const Matrix6& C, const std::vector<Stiffness>& phases,
                                   const std::vector<double>& f, double rel = 1e-9) {
  Matrix6 V = Matrix6::Zero(), S = Matrix6::Zero();
  for (std::size_t k = 0; k < phases.size(); ++k) {
    if (f[k] == 0)
      continue;
    V += f[k] * phases[k].matrix();
    S += f[k] * phases[k].matrix().inverse();
  }
  const Matrix6 R = S.inverse();
  const double scale = C.cwiseAbs().maxCoeff();
  Eigen::SelfAdjointEigenSolver<Matrix6> up(0.5 * ((V - C) + (V - C).transpose()));
  Eigen::SelfAdjointEigenSolver<Matrix6> lo(0.5 * ((C - R) + (C - R).transpose()));
  EXPECT_GE(up.eigenvalues().minCoeff(), -rel * scale) << "C above the Voigt bound";
  EXPECT_GE(lo.eigenvalues().minCoeff(), -rel * scale) << "C below the Reuss bound";
}

/// The symmetries of the balanced plain weave of cases/cells/plain-weave*.toml
/// (plain_weave_symmetry_test.cpp has the derivation): C11 = C22, C13 = C23,
/// C55 = C66 and every constant with an odd number of x or y indices zero
/// (orthotropic), each to @p tol (Pa).
inline void expectPlainWeaveSymmetry(const Matrix6& C, double tol) {
  EXPECT_NEAR(C(0, 0), C(1, 1), tol);
  EXPECT_NEAR(C(0, 2), C(1, 2), tol);
  EXPECT_NEAR(C(4, 4), C(5, 5), tol);
  for (int i = 0; i < 6; ++i)
    for (int j = std::max(i + 1, 3); j < 6; ++j)
      EXPECT_NEAR(C(i, j), 0.0, tol) << i << ", " << j;
}

/// A random symmetric positive definite stiffness (lamina order, Pa), well
/// conditioned: A A^T + 6 I scaled to GPa.
inline Stiffness randomStiffness(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Matrix6 A;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      A(i, j) = u(rng);
  return Stiffness((A * A.transpose() + 6 * Matrix6::Identity()) * 1e9);
}

/// Runs the homogenizer on a phase map.
inline homogenize::Result homogenizeMap(const std::array<int, 3>& n,
                                        const std::vector<std::int32_t>& phase,
                                        const std::vector<Stiffness>& C, double tol,
                                        std::vector<double> density = {},
                                        std::optional<homogenize::Precision> precision = {}) {
  if (density.empty())
    density.assign(C.size(), 1000.0);
  homogenize::Grid g;
  g.n = n;
  g.h = {1.0 / n[0], 1.0 / n[1], 1.0 / n[2]};
  homogenize::Options o;
  o.tol = tol;
  o.precision = precision;
  homogenize::Homogenizer h(g, phase, C, density, o);
  return h.run();
}

/// Runs the homogenizer on a generated cell as `homogenize` does: its
/// composite voxels (if any) enter with their laminate stiffness and mixed
/// density (micro::voxelMaterials), the other voxels with their phase's.
inline homogenize::Result homogenizeUnitCell(const micro::UnitCell& cell,
                                             const std::vector<Stiffness>& C, double tol,
                                             const std::vector<double>& density) {
  micro::VoxelMaterials vm = micro::voxelMaterials(cell, C, density);
  return homogenizeMap(cell.n, vm.phase, vm.C, tol, vm.density);
}

/// Relative max-norm distance of two matrices, relative to max |b|.
inline double relDiff(const Matrix6& a, const Matrix6& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

} // namespace lamina::test
