// Cell files that ask for more than can be done: counts that
// overflowed an int or ran for hours, resolutions that wrapped around or
// died in std::bad_alloc. Each is refused naming the file and the key.

#include "core/error.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <gtest/gtest.h>

namespace lamina::micro {
namespace {

const std::string kPhases = "[[phases]]\nname = \"m\"\nlaw = \"isotropic\"\nE = 1e9\nnu = 0.3\n"
                            "density = 1000\n[[phases]]\nname = \"i\"\nlaw = \"isotropic\"\n"
                            "E = 9e9\nnu = 0.2\ndensity = 2000\n";

std::string cell(const std::string& resolution, const std::string& inclusion = "") {
  return "[cell]\nresolution = " + resolution + "\n" + kPhases +
         (inclusion.empty() ? ""
                            : "[[inclusions]]\nphase = \"i\"\nshape = \"sphere\"\n" + inclusion);
}

/// The message of reading and building @p text ("" if it builds).
std::string errorOf(const std::string& text, std::array<int, 3> n = {0, 0, 0}) {
  try {
    buildCell(readCellString(text, "bad.toml", lazyCatalog()), n);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

void expectRefused(const std::string& msg, const std::vector<std::string>& parts) {
  ASSERT_FALSE(msg.empty());
  EXPECT_NE(msg.find("bad.toml"), std::string::npos) << msg;
  for (const auto& p : parts)
    EXPECT_NE(msg.find(p), std::string::npos) << "no '" << p << "' in: " << msg;
}

} // namespace

// 4294967304 = 2^32 + 8 became a resolution of 8 through a cast to int.
TEST(MalformedLimits, ResolutionIsRangeCheckedBeforeNarrowing) {
  expectRefused(errorOf(cell("4294967304")), {"cell.resolution", "4294967304"});
  expectRefused(errorOf(cell("[8, 8, 4294967304]")), {"cell.resolution"});
  expectRefused(errorOf(cell("[8, 8, 1e300]")), {"cell.resolution"});
  expectRefused(errorOf(cell("100000")), {"cell.resolution", "4096"});
}

// The largest resolution in range is refused by its memory (4096^3 voxels of
// 4 bytes, twice, is 512 GiB), with the amount, before any allocation.
TEST(MalformedLimits, ResolutionBeyondMemoryIsRefusedWithTheAmount) {
  expectRefused(errorOf(cell("8"), {4096, 4096, 4096}), {"resolution", "needs about", "GiB"});
  expectRefused(errorOf(cell("8"), {100000, 8, 8}), {"resolution", "4096"});
}

// lattice = [100000, 100000, 100000] overflowed an int (10^15 copies);
// count = 1000000000 or a tiny radius with a volume fraction placed for hours.
TEST(MalformedLimits, InclusionCountsAreBounded) {
  expectRefused(errorOf(cell("8", "radius = 0.01\nplacement = \"lattice\"\n"
                                  "lattice = [100000, 100000, 100000]\n")),
                {"inclusions[0].lattice", "10000"});
  expectRefused(errorOf(cell("8", "radius = 0.001\nplacement = \"random\"\n"
                                  "count = 1000000000\n")),
                {"inclusions[0].count", "10000"});
  expectRefused(errorOf(cell("8", "radius = 1e-6\nplacement = \"random\"\n"
                                  "volume_fraction = 0.2\n")),
                {"inclusions[0]", "volume_fraction"});
  expectRefused(errorOf(cell("8", "radius = 0.01\nplacement = \"random\"\ncount = 5\n"
                                  "max_attempts = 100000000000\n")),
                {"inclusions[0].max_attempts"});
}

// Random placement has a work bound (overlap tests, attempts x inclusions
// placed): an unplaceable cell at the largest count and attempts took
// hours. The bound is lowered here (no key sets it) so that reaching it
// takes a fraction of a second: 300 spheres of radius 0.1 hold 1.26 times
// the cell's volume, random sequential placement jams near 38 % (about 90
// of them), and every attempt after that tests all those placed, until the
// bound of 1e6 tests (the 1e6 attempts allowed per sphere would be ~1e8).
TEST(MalformedLimits, RandomPlacementStopsAtItsWorkBound) {
  CellSpec spec = readCellString(cell("8", "radius = 0.1\nplacement = \"random\"\n"
                                           "count = 300\nmax_attempts = 1000000\n"),
                                 "bad.toml", lazyCatalog());
  EXPECT_EQ(spec.max_overlap_tests, kMaxOverlapTests);
  spec.max_overlap_tests = 1000000;
  std::string msg;
  try {
    buildCell(spec);
  } catch (const Error& e) {
    msg = e.what();
  }
  expectRefused(msg, {"inclusions[0]", "1000000 overlap tests", "random placement stopped"});
}

} // namespace lamina::micro
