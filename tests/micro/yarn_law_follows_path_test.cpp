// A woven yarn's law follows its centre line (micro/yarn_orientation.hpp):
// each voxel's stiffness against the phase's C rotated by definition
// (test::rotateByDefinition, the full 3x3x3x3 tensor) to the tangent of the
// centre line at the voxel centre's foot point, the foot found here by a brute-force search
// of the whole period (not the Newton search of the code); a straight yarn
// and an isotropic yarn leave the voxel materials exactly as without the
// option.

#include "../materials/test_support.hpp"
#include "micro/cell.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/inclusion.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace lamina::micro {
namespace {

using materials::Matrix6;

// A triclinic, positive definite C (Pa, lamina order): a transversely
// isotropic glass bundle along x with small couplings of every kind, so
// that a rotation about any axis, or a wrong sign, changes some entry.
Matrix6 yarnC() {
  Matrix6 C;
  C << 48.37, 6.02, 6.02, 0.31, 0.17, 0.23, //
      6.02, 15.03, 6.46, 0.12, 0.29, 0.11,  //
      6.02, 6.46, 15.03, 0.21, 0.13, 0.27,  //
      0.31, 0.12, 0.21, 4.5, 0.09, 0.14,    //
      0.17, 0.29, 0.13, 0.09, 4.285, 0.07,  //
      0.23, 0.11, 0.27, 0.14, 0.07, 4.5;
  return C * 1e9;
}

std::string matrixToml(const Matrix6& C) {
  std::string s = "[";
  char buf[64];
  for (int i = 0; i < 6; ++i) {
    s += i ? ", [" : "[";
    for (int j = 0; j < 6; ++j) {
      std::snprintf(buf, sizeof buf, "%s%.17g", j ? ", " : "", C(i, j));
      s += buf;
    }
    s += "]";
  }
  return s + "]";
}

const char* kAxis[3] = {"x", "y", "z"};

// One yarn along @p a undulating along @p c in a cell of 2 x 1 x 0.5 mm
// (direction, width axis, crimp), 25 um voxels; lambda = 1 mm, A = 0.1 mm:
// the crimp angle reaches atan(A k) = 32 degrees.
std::string yarnCell(int a, int c, const std::string& yarnLaw, const std::string& extra) {
  const int w = 3 - a - c;
  double size[3], res[3];
  size[a] = 2e-3;
  size[w] = 1e-3;
  size[c] = 0.5e-3;
  for (int i = 0; i < 3; ++i)
    res[i] = size[i] / 2.5e-5;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "[cell]\nresolution = [%g, %g, %g]\nsize = [%g, %g, %g]\n"
                "[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 3.5e9\nnu = 0.35\n"
                "density = 1200\n",
                res[0], res[1], res[2], size[0], size[1], size[2]);
  std::string text = buf;
  text += "[[phases]]\nname = \"y\"\n" + yarnLaw + "\ndensity = 2000\n";
  text += "[[inclusions]]\nphase = \"y\"\nshape = \"yarn\"\ndirection = \"" +
          std::string(kAxis[a]) + "\"\ncrimp = \"" + kAxis[c] +
          "\"\nwidth = 0.4e-3\nthickness = 0.12e-3\nwavelength = 1e-3\n" + extra + "\n";
  return text;
}

const std::string kAnisotropic = "law = \"anisotropic\"\nC = " + matrixToml(yarnC());

// The foot of (s, z) on x_c = A sin(k x) by brute force: a scan of the
// whole period around s for the nearest sample (the nearest point of the
// curve, wherever it is), then bisection of the foot condition
// g(x) = (s - x) + (z - A sin kx) A k cos kx = 0 (minus half the slope of
// the squared distance: positive before the minimum, negative after) to
// round-off.
double bruteForceFoot(double A, double k, double s, double z) {
  auto d2 = [&](double x) { return (s - x) * (s - x) + std::pow(z - A * std::sin(k * x), 2); };
  auto g = [&](double x) { return (s - x) + (z - A * std::sin(k * x)) * A * k * std::cos(k * x); };
  const double lambda = 2 * M_PI / k;
  constexpr int kScan = 1000;
  double best = s, fb = d2(s);
  for (int i = 0; i <= kScan; ++i) {
    const double x = s - 0.5 * lambda + lambda * i / kScan;
    if (d2(x) < fb) {
      fb = d2(x);
      best = x;
    }
  }
  double lo = best - lambda / kScan, hi = best + lambda / kScan;
  EXPECT_GT(g(lo), 0);
  EXPECT_LT(g(hi), 0);
  for (int it = 0; it < 200 && lo < hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi)
      break;
    (g(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The yarn's C rotated to the tangent at the foot of voxel centre @p p:
// R e_a = t = cos th e_a + sin th e_c, R e_c = the path normal, R e_w = e_w.
Matrix6 expectedAt(const Inclusion& inc, const Eigen::Vector3d& p, const Eigen::Vector3d& L,
                   double& theta) {
  const Eigen::Vector3d d = nearestImage(p - inc.center, L);
  const double k = 2 * M_PI / inc.wavelength;
  const double xf = bruteForceFoot(inc.amplitude, k, d[inc.axis], d[inc.crimp]);
  theta = std::atan(inc.amplitude * k * std::cos(k * xf));
  Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
  const int a = inc.axis, c = inc.crimp, w = 3 - a - c;
  R(a, a) = std::cos(theta);
  R(c, a) = std::sin(theta);
  R(a, c) = -std::sin(theta);
  R(c, c) = std::cos(theta);
  R(w, w) = 1;
  return test::rotateByDefinition(yarnC(), R);
}

// Every whole yarn voxel's entry is the analytically rotated C, and the
// yarn side of every cut voxel's laminate is too, for yarns along each axis.
// Tolerance 1e-11 of max |C|: both feet are exact to round-off (bisection
// here, Newton stopped after a step of 1e-9 t/2 in the code, its error then
// ~1e-18 t), so theta agrees to ~1e-15 and both rotations of C to a few
// ulps of max |C| times the 81 terms summed; a wrong sign or axis is O(1).
TEST(YarnLawFollowsPath, VoxelStiffnessIsTheAnalyticallyRotatedC) {
  // (x, z): e_w x e_a = -e_c; (y, z) and (z, x): +e_c (both signs of phi)
  const int configs[3][2] = {{0, 2}, {1, 2}, {2, 0}};
  const Matrix6 Cy = yarnC();
  const double tol = 1e-11 * Cy.cwiseAbs().maxCoeff();
  for (const auto& ac : configs) {
    SCOPED_TRACE(std::string("direction ") + kAxis[ac[0]] + ", crimp " + kAxis[ac[1]]);
    const CellSpec spec = readCellString(yarnCell(ac[0], ac[1], kAnisotropic, "amplitude = 0.1e-3"),
                                         "yarn.toml", lazyCatalog());
    const UnitCell cell = buildCell(spec);
    const VoxelMaterials vm = voxelMaterials(cell, spec.stiffnessesAt(1.0), spec.densities());
    const Inclusion& inc = cell.inclusions.at(0);
    const Eigen::Vector3d h(cell.size[0] / cell.n[0], cell.size[1] / cell.n[1],
                            cell.size[2] / cell.n[2]);
    std::size_t whole = 0, cut = 0;
    double maxTheta = 0;
    for (std::size_t idx = 0; idx < cell.voxels(); ++idx) {
      const Eigen::Vector3d p = voxelCentre(idx, cell.n, h);
      const auto e = static_cast<std::size_t>(vm.phase[idx]);
      if (e == 0)
        continue;
      double theta = 0;
      const Matrix6 expected = expectedAt(inc, p, cell.size, theta);
      if (e == 1) {
        ADD_FAILURE() << "yarn voxel " << idx << " keeps the unrotated phase";
        continue;
      }
      ASSERT_LT(e, vm.C.size());
      Matrix6 got = vm.C[e].matrix();
      if (const CompositeVoxel* v = findVoxel(cell.composites, idx)) {
        // a cut voxel: the laminate of the rotated yarn C and the matrix
        got -= laminateStiffness(materials::Stiffness(expected), vm.C[0], v->fraction, v->normal)
                   .matrix();
        ++cut;
      } else {
        got -= expected;
        ++whole;
      }
      EXPECT_LE(got.cwiseAbs().maxCoeff(), tol) << "voxel " << idx << ", theta " << theta;
      maxTheta = std::max(maxTheta, std::abs(theta));
    }
    // both kinds seen, and crimp angles up to nearly atan(A k) = 32.1 degrees
    EXPECT_GT(whole, 1000u);
    EXPECT_GT(cut, 1000u);
    EXPECT_GT(maxTheta, 31.0 * M_PI / 180);
    EXPECT_EQ(cell.oriented.size(), whole + cut);
    // whole voxels share their rotation's entry: the foot depends only on the
    // coordinates along the yarn and the crimp axis, so there are at most
    // n_a n_c rotations (the grid's rows across the width)
    const std::size_t rotations = vm.C.size() - 2 - cell.composites.size();
    EXPECT_LE(rotations, static_cast<std::size_t>(cell.n[static_cast<std::size_t>(inc.axis)] *
                                                  cell.n[static_cast<std::size_t>(inc.crimp)]));
    EXPECT_LT(3 * rotations, whole);
  }
}

// A straight yarn (A = 0): tangent = direction everywhere, so the voxel
// materials are those without the option, bit for bit (no entry added).
TEST(YarnLawFollowsPath, StraightYarnGivesExactlyTheUnrotatedMaterials) {
  const CellSpec on = readCellString(yarnCell(0, 2, kAnisotropic, ""), "yarn.toml", lazyCatalog());
  const CellSpec off = readCellString(yarnCell(0, 2, kAnisotropic, "follow_path = false"),
                                      "yarn.toml", lazyCatalog());
  const UnitCell a = buildCell(on), b = buildCell(off);
  EXPECT_TRUE(a.oriented.empty());
  const VoxelMaterials va = voxelMaterials(a, on.stiffnessesAt(1.0), on.densities());
  const VoxelMaterials vb = voxelMaterials(b, off.stiffnessesAt(1.0), off.densities());
  EXPECT_EQ(va.phase, vb.phase);
  ASSERT_EQ(va.C.size(), vb.C.size());
  for (std::size_t e = 0; e < va.C.size(); ++e)
    EXPECT_TRUE(va.C[e].matrix() == vb.C[e].matrix()) << "entry " << e;
}

// An isotropic yarn keeps the fast path: a rotation leaves its C as it is,
// so no voxel gets its own entry (only the cut voxels' laminates).
TEST(YarnLawFollowsPath, IsotropicYarnCreatesNoPerVoxelEntries) {
  const CellSpec spec = readCellString(
      yarnCell(0, 2, "law = \"isotropic\"\nE = 40e9\nnu = 0.25", "amplitude = 0.1e-3"), "yarn.toml",
      lazyCatalog());
  const UnitCell cell = buildCell(spec);
  EXPECT_TRUE(cell.oriented.empty());
  const VoxelMaterials vm = voxelMaterials(cell, spec.stiffnessesAt(1.0), spec.densities());
  EXPECT_EQ(vm.C.size(), 2 + cell.composites.size());
}

} // namespace
} // namespace lamina::micro
