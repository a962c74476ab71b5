// Bad [[blast]] tables in a case file: each error names the file, the key
// and the cause.
#include "helpers.hpp"

#include <gtest/gtest.h>

using namespace lamina::membrane;

namespace {
const std::string kPanel = test::blastPanel(2, 1.0e-3);

std::string errorOf(const std::string& blast) {
  try {
    test::modelFromText(kPanel + "[[blast]]\n" + blast, "bad-blast.toml");
  } catch (const lamina::Error& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}
} // namespace

TEST(BlastCaseMalformed, GoodBlastBuilds) {
  EXPECT_EQ(errorOf("charge = 0.05\nposition = [0.5, 0.5, -2.0]\n"), "");
}

TEST(BlastCaseMalformed, ErrorsNameTheKey) {
  const auto neg = errorOf("charge = -1.0\nposition = [0.5, 0.5, -2.0]\n");
  EXPECT_TRUE(has(neg, "bad-blast.toml")) << neg;
  EXPECT_TRUE(has(neg, "charge")) << neg;
  const auto pos = errorOf("charge = 1.0\nposition = [0.5, 0.5]\n");
  EXPECT_TRUE(has(pos, "position")) << pos;
  const auto burst = errorOf("charge = 1.0\nposition = [0, 0, -2]\nburst = \"airburst\"\n");
  EXPECT_TRUE(has(burst, "burst")) << burst;
  EXPECT_TRUE(has(burst, "airburst")) << burst;
  const auto both = errorOf("charge = 1.0\nposition = [0, 0, -2]\ntable = \"p.csv\"\n");
  EXPECT_TRUE(has(both, "either charge")) << both;
  // 100 kg at 2 m: Z = 0.43 is fine; 1000 kg at 0.3 m: Z = 0.03 is refused,
  // naming the element and the scaled distance.
  const auto close = errorOf("charge = 1000.0\nposition = [0.5, 0.5, -0.3]\n");
  EXPECT_TRUE(has(close, "element")) << close;
  EXPECT_TRUE(has(close, "scaled distance")) << close;
  const auto clamp =
      errorOf("charge = 1000.0\nposition = [0.5, 0.5, -0.3]\nout_of_range = \"clamp\"\n");
  EXPECT_EQ(clamp, "");
}
