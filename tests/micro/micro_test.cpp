// Unit cells: volume fractions reached, non-overlap of random placement,
// orientation of ellipsoids, phase laws (GVBO moduli at J against hand
// values), phase map file round trip.

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "micro/cell.hpp"
#include "micro/phase_map_io.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <fstream>
#include <unistd.h>

namespace lamina::micro {
namespace {

const std::string kPhases =
    "[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\ndensity = 1000\n"
    "[[phases]]\nname = \"i\"\nlaw = \"isotropic\"\nE = 9e9\nnu = 0.2\ndensity = 2000\n";

CellSpec spec(int N, const std::string& inclusions) {
  return readCellString("[cell]\nresolution = " + std::to_string(N) + "\n" + kPhases +
                            "[[inclusions]]\nphase = \"i\"\n" + inclusions,
                        "test.toml", lazyCatalog());
}

// The analytic fraction equals the target exactly (lengths are scaled to it);
// the voxel fraction converges to it: for a sphere of radius R voxels the
// staircase error is O(1/R), about 1 % at 64^3 (R = 21).
TEST(VolumeFraction, SingleSphereReachesTarget) {
  const auto s = spec(64, "shape = \"sphere\"\nradius = 0.2\nvolume_fraction = 0.19\n");
  const UnitCell c = buildCell(s);
  EXPECT_NEAR(c.analytic_fraction[0], 0.19, 1e-14);
  EXPECT_NEAR(c.voxel_fraction[1], 0.19, 0.19 * 0.01);
  EXPECT_NEAR(c.voxel_fraction[0] + c.voxel_fraction[1], 1.0, 1e-14);
  const double r = std::cbrt(0.19 * 3 / (4 * M_PI)); // radius of a 19 % sphere
  EXPECT_NEAR(c.inclusions[0].semi[0], r, 1e-14);
}

// Lattice, fiber and layer fractions: pi r^2 for a fiber (area fraction),
// the thickness for a layer (exact on voxel boundaries: 8 of 32 voxels).
TEST(VolumeFraction, LatticeFiberAndLayer) {
  const UnitCell lat = buildCell(spec(48, "shape = \"sphere\"\nradius = 0.1\nplacement = "
                                          "\"lattice\"\nlattice = [2, 2, 2]\nvolume_fraction = "
                                          "0.3\n"));
  EXPECT_EQ(lat.inclusions.size(), 8u);
  EXPECT_NEAR(lat.voxel_fraction[1], 0.3, 0.3 * 0.03); // R = 9.9 voxels: ~3 %
  const UnitCell fib = buildCell(spec(64, "shape = \"fiber\"\ndirection = [0, 0, 1]\nradius = "
                                          "0.2\nvolume_fraction = 0.5\n"));
  EXPECT_NEAR(fib.inclusions[0].radius, std::sqrt(0.5 / M_PI), 1e-14);
  EXPECT_NEAR(fib.voxel_fraction[1], 0.5, 0.5 * 0.01);
  const UnitCell lay = buildCell(spec(32, "shape = \"layer\"\nnormal = \"y\"\nthickness = 0.25\n"));
  EXPECT_DOUBLE_EQ(lay.voxel_fraction[1], 0.25);
}

// Random sequential placement: the requested count, reproducible from the
// seed, and every pair of spheres at least 2 r + min_gap apart (nearest
// periodic image), checked independently of the placement code.
TEST(RandomPlacement, NonOverlappingWithGapAndReproducible) {
  const std::string inc = "shape = \"sphere\"\nradius = 0.08\nplacement = \"random\"\ncount = "
                          "30\nvolume_fraction = 0.25\nseed = 9\nmin_gap = 0.03\n";
  const UnitCell a = buildCell(spec(32, inc)), b = buildCell(spec(32, inc));
  ASSERT_EQ(a.inclusions.size(), 30u);
  const double r = a.inclusions[0].semi[0];
  EXPECT_NEAR(30 * 4.0 / 3.0 * M_PI * r * r * r, 0.25, 1e-12);
  for (std::size_t p = 0; p < a.inclusions.size(); ++p) {
    EXPECT_EQ(a.inclusions[p].center, b.inclusions[p].center);
    for (std::size_t q = p + 1; q < a.inclusions.size(); ++q) {
      Eigen::Vector3d d = a.inclusions[p].center - a.inclusions[q].center;
      for (int k = 0; k < 3; ++k)
        d[k] -= std::round(d[k]);
      EXPECT_GE(d.norm(), 2 * r + 0.03 - 1e-12);
    }
  }
  EXPECT_EQ(a.phase, b.phase);
  EXPECT_NEAR(a.voxel_fraction[1], 0.25, 0.25 * 0.05); // R = 2.6 voxels: staircase ~5 %
}

// An ellipsoid with semi-axes (0.1, 0.1, 0.3) rotated by 90 degrees about y
// has its long axis along x: the point 0.25 along x from the centre is
// inside, the point 0.25 along z is outside. At 45 degrees both points
// along (1, 0, 1)/sqrt 2 at 0.25 are inside / outside accordingly.
TEST(Ellipsoid, OrientationRotatesTheLongAxis) {
  auto build = [](double angle) {
    return readCellString("[cell]\nresolution = 8\n" + kPhases +
                              "[[inclusions]]\nphase = \"i\"\nshape = \"ellipsoid\"\nsemi_axes = "
                              "[0.1, 0.1, 0.3]\norientation = { axis = [0, 1, 0], angle = " +
                              std::to_string(angle) + " }\n",
                          "t.toml", lazyCatalog());
  };
  const Eigen::Vector3d L = Eigen::Vector3d::Ones(), c(0.5, 0.5, 0.5);
  const UnitCell q = buildCell(build(90));
  EXPECT_TRUE(q.inclusions[0].contains(c + Eigen::Vector3d(0.25, 0, 0), L));
  EXPECT_FALSE(q.inclusions[0].contains(c + Eigen::Vector3d(0, 0, 0.25), L));
  const UnitCell h = buildCell(build(45));
  const double s = 0.25 / std::sqrt(2.0);
  EXPECT_TRUE(h.inclusions[0].contains(c + Eigen::Vector3d(s, 0, s), L));
  EXPECT_FALSE(h.inclusions[0].contains(c + Eigen::Vector3d(-s, 0, s), L));
}

// GVBO moduli at J (chapter eqs. 13-16) for the Table 11 soft domains
// (E0 = 156 MPa, nu0 = 0.494, p = -6), against values computed by hand:
// lambda0 = E nu/((1+nu)(1-2nu)) = 4298.5274 MPa, G0 = E/(2(1+nu)) = 52.208835 MPa;
// J = 0.95: lambda = 0.95^-6 lambda0 = 5847.6056 MPa,
//           G = 0.95^-6 (G0 - lambda0 ln 0.95) = 370.96650 MPa;
// J = 1.05: eq. (13) would lower lambda and G: both stay at lambda0, G0.
TEST(GvboPhase, ModuliAtJMatchHandValues) {
  const std::string text =
      "[cell]\nresolution = 4\n[[phases]]\nname = \"soft\"\nlaw = \"gvbo\"\nE = 156e6\nnu = "
      "0.494\ndensity = 1100\nJ = [1.0, 0.95, 1.05]\n[phases.gvbo]\nEt = 23.3e6\np = -6\na1 = "
      "0\na2 = 10e6\na3 = 0\nk1 = 17\nk2 = 0.47e6\nk3 = 1.47e6\nk4 = 4\nEm = 13600e6\nA0 = "
      "1e6\nAc = 0\nAf = 0\n";
  const CellSpec s = readCellString(text, "gvbo.toml", lazyCatalog());
  ASSERT_EQ(s.sweepStates().size(), 3u);
  const auto C1 = s.phases[0].stiffnessAt(1.0);
  const auto C95 = s.phases[0].stiffnessAt(0.95);
  const auto C105 = s.phases[0].stiffnessAt(1.05);
  const double lambda0 = 4298.5274e6, G0 = 52.208835e6;
  EXPECT_NEAR(C1(0, 1), lambda0, 1e-7 * lambda0);
  EXPECT_NEAR(C1(3, 3), G0, 1e-7 * G0);
  EXPECT_NEAR(C95(0, 1), 5847.6056e6, 1e-7 * 5847.6056e6);
  EXPECT_NEAR(C95(3, 3), 370.96650e6, 1e-7 * 370.96650e6);
  EXPECT_NEAR(C105(0, 1), lambda0, 1e-7 * lambda0);
  EXPECT_NEAR(C105(3, 3), G0, 1e-7 * G0);
}

// /phases is int32 N1 x N2 x N3 in C order with x slowest; the XDMF names it.
TEST(PhaseMap, WritesHdf5AndXdmfThatReadBack) {
  const auto s = spec(6, "shape = \"layer\"\nnormal = \"x\"\nthickness = 0.4\n");
  UnitCell c = buildCell(s, {6, 4, 2});
  const auto dir = std::filesystem::temp_directory_path() /
                   (std::string("lamina-micro-test") + "-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto h5 = dir / "phases.h5";
  writePhaseMap(c, {"m", "i"}, h5);
  core::H5File f(h5, core::H5File::Mode::ReadOnly);
  std::vector<std::uint64_t> dims;
  const auto data = f.readInts("/phases", dims);
  EXPECT_EQ(dims, (std::vector<std::uint64_t>{6, 4, 2}));
  // x slowest: the layer |x - 0.5| <= 0.2 covers voxels i = 2, 3 (centres 5/12, 7/12)
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(data[static_cast<std::size_t>(i * 8)], (i == 2 || i == 3) ? 1 : 0) << i;
  EXPECT_EQ(readPhaseMap(h5, 2).phase, c.phase);
  std::ifstream x(dir / "phases.xdmf");
  std::string xml((std::istreambuf_iterator<char>(x)), std::istreambuf_iterator<char>());
  EXPECT_NE(xml.find("phases.h5:/phases"), std::string::npos);
  EXPECT_NE(xml.find("Dimensions=\"7 5 3\""), std::string::npos);
  x.close();
  std::filesystem::remove_all(dir);
}

} // namespace
} // namespace lamina::micro
