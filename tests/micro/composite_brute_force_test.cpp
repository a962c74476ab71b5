// Composite voxels against a brute-force count: the cell build skips whole
// voxels by a distance bound, decides most sub-samples from a quadratic
// form and walks only near the surface (micro/inside_query.hpp); none of
// that may change the result. Here every voxel of the grid is tested
// directly with Inclusion::contains: the centre for the phase map, the 8
// corners for "cut", and then the 10^3 sub-samples for the fraction, and
// the cell's phase map, composite voxels and fractions must equal that
// count exactly (the same points, the same predicate: no tolerance).
// Shapes: a sphere and a rotated ellipsoid across the periodic boundary,
// fibres along x and z (a sub-sample line along the z-fibre is constant),
// random spheres of two phases (voxels shared by two inclusions) and a
// crimped yarn.

#include "micro/cell.hpp"
#include "micro/composite_voxel.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

using namespace lamina::micro;

namespace {

const std::string kPhases =
    "[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n"
    "[[phases]]\nname = \"f\"\nlaw = \"isotropic\"\nE = 9e9\nnu = 0.2\ndensity = 2000\n"
    "[[phases]]\nname = \"g\"\nlaw = \"isotropic\"\nE = 5e9\nnu = 0.25\ndensity = 1500\n";

UnitCell cellOf(const std::string& head, const std::string& inclusions) {
  return buildCell(readCellString("[cell]\n" + head + "\n" + kPhases + inclusions,
                                  "brute_force.toml", lazyCatalog()),
                   {0, 0, 0});
}

/// The phase map and composite fractions by testing every point with
/// Inclusion::contains (the rules of composite_voxel.hpp: a voxel is cut
/// when its corners disagree; fractions of one phase add up; two phases
/// in a voxel keep the centre's; all sub-samples on one side set the phase).
void bruteForce(const UnitCell& cell, std::vector<std::int32_t>& phase,
                std::map<std::size_t, double>& fraction) {
  const std::array<int, 3>& n = cell.n;
  const Eigen::Vector3d& L = cell.size;
  const Eigen::Vector3d h(L[0] / n[0], L[1] / n[1], L[2] / n[2]);
  constexpr int s = kSubSamples;
  phase.assign(cell.phase.size(), 0);
  fraction.clear();
  std::size_t idx = 0;
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k, ++idx) {
        const Eigen::Vector3d corner(i * h[0], j * h[1], k * h[2]);
        int count = 0, cutPhase = -1;
        bool onePhase = true;
        for (const Inclusion& inc : cell.inclusions) {
          if (inc.contains(Eigen::Vector3d((i + 0.5) * h[0], (j + 0.5) * h[1], (k + 0.5) * h[2]),
                           L))
            phase[idx] = inc.phase;
          int in = 0;
          for (int c = 0; c < 8; ++c)
            in += inc.contains(corner + Eigen::Vector3d((c & 1) * h[0], ((c >> 1) & 1) * h[1],
                                                        ((c >> 2) & 1) * h[2]),
                               L);
          if (in == 0 || in == 8)
            continue;
          onePhase = onePhase && (cutPhase < 0 || cutPhase == inc.phase);
          cutPhase = inc.phase;
          for (int a = 0; a < s; ++a)
            for (int b = 0; b < s; ++b)
              for (int c = 0; c < s; ++c)
                count += inc.contains(corner + Eigen::Vector3d((a + 0.5) / s * h[0],
                                                               (b + 0.5) / s * h[1],
                                                               (c + 0.5) / s * h[2]),
                                      L);
        }
        if (cutPhase < 0 || !onePhase)
          continue;
        if (count == 0 || count >= s * s * s)
          phase[idx] = count == 0 ? 0 : cutPhase;
        else
          fraction[idx] = static_cast<double>(count) / (s * s * s);
      }
}

void expectBruteForce(const UnitCell& cell) {
  std::vector<std::int32_t> phase;
  std::map<std::size_t, double> fraction;
  bruteForce(cell, phase, fraction);
  ASSERT_FALSE(fraction.empty());
  EXPECT_EQ(cell.phase, phase);
  ASSERT_EQ(cell.composites.size(), fraction.size());
  auto it = fraction.begin();
  for (const CompositeVoxel& v : cell.composites) {
    EXPECT_EQ(v.index, it->first);
    EXPECT_EQ(v.fraction, it->second) << "voxel " << v.index;
    ++it;
  }
}

const std::string kCell = "size = [1e-3, 1.25e-3, 0.8e-3]\nresolution = [20, 24, 16]";

} // namespace

TEST(CompositeBruteForce, SphereAcrossTheBoundary) {
  expectBruteForce(cellOf(kCell, "[[inclusions]]\nphase = \"f\"\nshape = \"sphere\"\n"
                                 "radius = 0.3e-3\ncenter = [0.05e-3, 1.2e-3, 0.4e-3]\n"));
}

TEST(CompositeBruteForce, RotatedEllipsoidAcrossTheBoundary) {
  expectBruteForce(cellOf(kCell, "[[inclusions]]\nphase = \"f\"\nshape = \"ellipsoid\"\n"
                                 "semi_axes = [0.3e-3, 0.15e-3, 0.1e-3]\n"
                                 "center = [0.95e-3, 0.1e-3, 0.7e-3]\n"
                                 "[inclusions.orientation]\naxis = [1, 2, 3]\nangle = 37\n"));
}

TEST(CompositeBruteForce, FibresAlongXAndZ) {
  expectBruteForce(cellOf(kCell, "[[inclusions]]\nphase = \"f\"\nshape = \"fiber\"\n"
                                 "direction = \"x\"\nradius = 0.15e-3\n"
                                 "center = [0, 0.9e-3, 0.4e-3]\n"
                                 "[[inclusions]]\nphase = \"g\"\nshape = \"fiber\"\n"
                                 "direction = \"z\"\nradius = 0.15e-3\n"
                                 "center = [0.3e-3, 0.3e-3, 0]\n"));
}

TEST(CompositeBruteForce, RandomSpheresOfTwoPhases) {
  expectBruteForce(cellOf(kCell,
                          "[[inclusions]]\nphase = \"f\"\nshape = \"sphere\"\n"
                          "radius = 0.1e-3\nplacement = \"random\"\ncount = 8\nseed = 7\n"
                          "[[inclusions]]\nphase = \"g\"\nshape = \"sphere\"\n"
                          "radius = 0.08e-3\nplacement = \"random\"\ncount = 8\nseed = 3\n"));
}

TEST(CompositeBruteForce, CrimpedYarn) {
  expectBruteForce(cellOf("size = [2e-3, 2e-3, 0.5e-3]\nresolution = [24, 24, 8]",
                          "[[inclusions]]\nphase = \"f\"\nshape = \"yarn\"\ndirection = \"x\"\n"
                          "crimp = \"z\"\nwidth = 0.8e-3\nthickness = 0.16e-3\n"
                          "amplitude = 0.1e-3\ncenter = [0.3e-3, 0.5e-3, 0.25e-3]\n"));
}
