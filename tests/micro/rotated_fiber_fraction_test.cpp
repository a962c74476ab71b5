// Fibres along any lattice direction [u, v, w] (periodic: the axis runs along
// A = u Lx ex + v Ly ey + w Lz ez and re-enters the cell through its
// periodic images): the voxel fraction equals the analytic pi r^2 |A| / V
// to sampling accuracy, and with composite voxels to quadrature accuracy.
// Also the exact plane-cut fraction of a box (used for layers) against
// independent cases.

#include "core/error.hpp"
#include "micro/cell.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace lamina::micro {
namespace {

const Eigen::Vector3d kSize(1e-3, 1.25e-3, 0.8e-3); // m: a non-cubic cell

UnitCell fiberCell(const std::string& uvw, double r, int N, bool composite) {
  const std::string text =
      "[cell]\nresolution = " + std::to_string(N) + "\nsize = [1e-3, 1.25e-3, 0.8e-3]\n" +
      "composite_voxels = " + (composite ? "true" : "false") +
      "\n[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n"
      "[[phases]]\nname = \"f\"\nlaw = \"isotropic\"\nE = 9e9\nnu = 0.2\ndensity = 2000\n"
      "[[inclusions]]\nphase = \"f\"\nshape = \"fiber\"\ndirection = " +
      uvw + "\nradius = " + std::to_string(r) + "\ncenter = [3e-4, 7e-4, 1e-4]\n";
  return buildCell(readCellString(text, "fiber.toml", lazyCatalog()), {N, N, N});
}

struct Case {
  std::string uvw;
  Eigen::Vector3d A; // the fibre's lattice vector (m)
  double r;          // radius (m)
};

// Analytic fraction: the axis crosses the cell once per lattice vector A,
// so the fibre holds a length |A| of cylinder: pi r^2 |A| / V (r below half
// the distance between parallel copies, so copies do not overlap).
//
// Bounds. Staircase: a voxel is misassigned only if the surface passes
// through it, so the error is at most the volume within a voxel diagonal d
// of the surface, 2 d S / V with S = 2 pi r |A| the lateral area.
// Composite voxels: the same argument on the sub-voxel grid (10 samples per
// edge) gives 2 (d / 10) S / V; the corner test misses at most slivers of
// height h^2 / (8 r) (chord sagitta) at voxels it does not flag, far below.
// The measured errors are much smaller than these worst cases (errors of
// both signs cancel around the fibre): staircase 1e-4 to 1e-3, composite
// 1e-6 to 1e-5 of the cell.
TEST(RotatedFibers, VoxelFractionsMatchTheAnalyticVolume) {
  const std::vector<Case> cases{
      {"[1, 1, 0]", Eigen::Vector3d(kSize[0], kSize[1], 0), 1.1e-4},
      {"[0, 1, -1]", Eigen::Vector3d(0, kSize[1], -kSize[2]), 1.2e-4},
      {"[1, 2, 3]", Eigen::Vector3d(kSize[0], 2 * kSize[1], 3 * kSize[2]), 6e-5},
      {"[2, -1, 1]", Eigen::Vector3d(2 * kSize[0], -kSize[1], kSize[2]), 8e-5}};
  const int N = 32;
  const double V = kSize.prod();
  const double d = std::sqrt(3.0) * kSize.maxCoeff() / N;
  double sumStair = 0, sumComposite = 0;
  for (const Case& c : cases) {
    const double f = M_PI * c.r * c.r * c.A.norm() / V;
    const double S = 2 * M_PI * c.r * c.A.norm();
    const UnitCell stair = fiberCell(c.uvw, c.r, N, false);
    const UnitCell comp = fiberCell(c.uvw, c.r, N, true);
    EXPECT_NEAR(stair.analytic_fraction[0], f, 1e-12 * f) << c.uvw;
    const double es = stair.voxel_fraction[1] - f, ec = comp.voxel_fraction[1] - f;
    EXPECT_LT(std::abs(es), 2 * d * S / V) << c.uvw;
    EXPECT_LT(std::abs(ec), 2 * d / 10 * S / V) << c.uvw;
    EXPECT_FALSE(comp.composites.empty()) << c.uvw;
    EXPECT_NEAR(comp.voxel_fraction[0] + comp.voxel_fraction[1], 1.0, 1e-12);
    sumStair += std::abs(es);
    sumComposite += std::abs(ec);
    std::printf("%s f %.6f staircase %+.2e (bound %.1e) composite %+.2e (bound %.1e), %zu cut\n",
                c.uvw.c_str(), f, es, 2 * d * S / V, ec, 2 * d / 10 * S / V,
                comp.composites.size());
  }
  // over the four directions the composite fractions are at least ten times
  // closer (the sub-grid is ten times finer)
  EXPECT_LT(sumComposite, sumStair / 10);
}

// A fibre wider than half the distance between its parallel copies would
// overlap itself through the periodic images: refused with the group named.
TEST(RotatedFibers, FibreWiderThanItsCopiesSpacingIsRefused) {
  try {
    fiberCell("[1, 2, 3]", 3e-4, 8, true);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("inclusions[0]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("spacing"), std::string::npos) << e.what();
  }
}

// The plane-cut fraction of a box against cases known independently: half
// of any box through its centre, the corner tetrahedron (volume a^3 / 6 /
// (m1 m2 m3) below m.x = a near a corner), a plane parallel to an axis
// (the 2-D triangle), and Monte Carlo sampling of a random plane.
TEST(PlaneCutFraction, MatchesIndependentCases) {
  const Eigen::Vector3d h(1.0, 2.0, 0.5);
  const Eigen::Vector3d nu = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  EXPECT_NEAR(boxFractionBelowPlane(h, nu, 0.0), 0.5, 1e-14);
  // corner (-h/2 with the signs of nu flipped): the lowest point of the box
  const Eigen::Vector3d low(-0.5 * h[0], 0.5 * h[1], -0.5 * h[2]);
  const double a = 0.05; // above the lowest corner: a tetrahedron
  const double tet = a * a * a / (6 * std::abs(nu[0] * nu[1] * nu[2])) / h.prod();
  EXPECT_NEAR(boxFractionBelowPlane(h, nu, nu.dot(low) + a), tet, 1e-12);
  const Eigen::Vector3d flat = Eigen::Vector3d(1, 1, 0).normalized();
  const double b = 0.3; // triangle of legs b sqrt2 in the x-y face corner
  EXPECT_NEAR(boxFractionBelowPlane(h, flat, -0.5 * (h[0] + h[1]) / std::sqrt(2.0) + b),
              0.5 * (b * std::sqrt(2.0)) * (b * std::sqrt(2.0)) / (h[0] * h[1]), 1e-12);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const double cut = 0.2;
  int below = 0;
  const int samples = 400000;
  for (int s = 0; s < samples; ++s)
    below += nu.dot(Eigen::Vector3d(u(rng) * h[0], u(rng) * h[1], u(rng) * h[2])) <= cut;
  // binomial standard deviation sqrt(p (1 - p) / n) < 8e-4: 5 of them
  EXPECT_NEAR(boxFractionBelowPlane(h, nu, cut), double(below) / samples, 4e-3);
}

} // namespace
} // namespace lamina::micro
