// formatExact: %.17g text parses back to the very same double (17 significant
// digits suffice for IEEE 754 binary64) and always reads as a TOML float.

#include "core/format.hpp"
#include "core/toml_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>

namespace core = lamina::core;

namespace {

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Checks the round trip through strtod and through the TOML parser.
void expectRoundTrip(double x) {
  const std::string s = core::formatExact(x);
  EXPECT_EQ(bits(std::strtod(s.c_str(), nullptr)), bits(x)) << s;
  const toml::table t = core::parseTomlString("v = " + s, "formatExact");
  const auto v = t["v"].value_exact<double>();
  ASSERT_TRUE(v.has_value()) << s << " is not a TOML float";
  EXPECT_EQ(bits(*v), bits(x)) << s;
}

} // namespace

TEST(FormatExact, SpecialValuesRoundTrip) {
  for (double x :
       {0.0, -0.0, 1.0, -1.0, 0.1, 1.0 / 3.0, 1e308, -1e308, DBL_MAX, DBL_MIN,
        std::numeric_limits<double>::denorm_min(), 4.9406564584124654e-324, 2.2250738585072009e-308,
        1e16, 1e17, 123456789012345678.0, 150e9, 2.0 / 3.0 * 1e-300})
    expectRoundTrip(x);
  EXPECT_EQ(core::formatExact(2.0), "2.0"); // integral values keep a '.', so TOML sees a float
  EXPECT_EQ(core::formatExact(0.1), "0.10000000000000001");
  EXPECT_EQ(core::formatExact(INFINITY), "inf");
}

// 20000 random bit patterns: all exponents, subnormals included.
TEST(FormatExact, RandomBitPatternsRoundTrip) {
  std::mt19937_64 rng(2026);
  int subnormals = 0;
  for (int k = 0; k < 20000; ++k) {
    std::uint64_t b = rng();
    if (k % 10 == 0)
      b &= 0x800FFFFFFFFFFFFFull; // force a subnormal
    double x;
    std::memcpy(&x, &b, sizeof x);
    if (!std::isfinite(x))
      continue;
    subnormals += std::fpclassify(x) == FP_SUBNORMAL;
    expectRoundTrip(x);
  }
  EXPECT_GT(subnormals, 1000);
}

TEST(FormatShort, UsesRequestedDigits) {
  EXPECT_EQ(core::formatShort(3.14159265, 3), "3.14");
  EXPECT_EQ(core::formatShort(1.5e-7), "1.5e-07");
  // the round-off tail of a sum is not shown: 0.0008 as a run summed it
  // (0.0008000000000000014, 17 digits) prints as 0.0008
  EXPECT_EQ(core::formatShort(0.0008000000000000014), "0.0008");
  EXPECT_EQ(core::formatShort(1.234567e-7), "1.23457e-07"); // 6 digits, rounded
  EXPECT_EQ(core::formatShort(1.234567e-7, 4), "1.235e-07");
  EXPECT_EQ(core::formatShort(123456789.0), "1.23457e+08");
  EXPECT_EQ(core::formatShort(-2.5), "-2.5");
}

// A width right-aligns the number (tables); a longer number is not cut.
TEST(FormatShort, WidthRightAligns) {
  EXPECT_EQ(core::formatShort(0.25, 4, 8), "    0.25");
  EXPECT_EQ(core::formatShort(-1.234567e-7, 4, 5), "-1.235e-07");
}

// A word of a suggested command: paths pass unchanged, anything a shell
// would split or expand is single-quoted, a quote inside closed and escaped.
TEST(ShellWord, QuotesOnlyWhatAShellWouldSplit) {
  EXPECT_EQ(core::shellWord("/home/a/lib-1.toml"), "/home/a/lib-1.toml");
  EXPECT_EQ(core::shellWord("my lib.toml"), "'my lib.toml'");
  EXPECT_EQ(core::shellWord("$HOME"), "'$HOME'");
  EXPECT_EQ(core::shellWord("it's"), "'it'\\''s'");
  EXPECT_EQ(core::shellWord(""), "''");
}

// A 6x6 matrix as text: one row per line, each value right-aligned in its
// column, scaled (Pa -> GPa), a negative zero shown as 0.
TEST(FormatMatrix6, RowsOfAlignedScaledValues) {
  struct Diagonal {
    double operator()(int i, int j) const { return i == j ? 1.5e9 * (i + 1) : -0.0; }
  };
  const std::string text = core::formatMatrix6(Diagonal{}, 1e-9, 4, 6, " ");
  EXPECT_EQ(text.substr(0, text.find('\n') + 1), "     1.5      0      0      0      0      0\n");
  EXPECT_EQ(text.substr(text.rfind('\n', text.size() - 2) + 1),
            "       0      0      0      0      0      9\n");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 6);
}
