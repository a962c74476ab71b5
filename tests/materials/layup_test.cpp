// Layups against the exact thickness average D = sum h_k R_k D_k R_k^T / h
// of DESIGN.md computed by hand, in-plane isotropy of a quasi-isotropic
// stack, and rejection of bad plies.

#include "core/error.hpp"
#include "materials/catalog.hpp"
#include "materials/layup.hpp"
#include "materials/symmetry.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <map>

namespace mat = lamina::materials;
using lamina::test::relDiff;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double GPa = 1e9;
// Power-of-two thicknesses: h_k C, their sums of two terms of equal exponent
// and the division by h are exact in binary floating point, so the expected
// averages below hold to the last bit.
constexpr double kH = 0.0009765625; // 2^-10 m, about 1 mm

class LayupTest : public ::testing::Test {
protected:
  LayupTest() : cat_(lamina::test::catalogPath()) {
    for (const char* n : {"table1-anisotropic", "aramid", "e-glass", "vinyl-fabric"})
      mats_[n] = cat_.get(n).toMaterial();
  }
  mat::MaterialLookup lookup() const {
    return [this](const std::string& n) {
      auto it = mats_.find(n);
      if (it == mats_.end())
        throw lamina::Error("unknown ply material", {"", 0, n});
      return it->second;
    };
  }
  mat::Material layup(const std::vector<mat::Ply>& plies) const {
    return mat::makeLayup("stack", plies, lookup());
  }
  mat::Catalog cat_;
  std::map<std::string, mat::Material> mats_;
};

} // namespace

// [0/90] of Table 1, by hand: the 90-degree ply swaps x and y, so
// C11 = C22 = (150 + 150)/2, C12 = 40, C13 = C23 = (10 + 80)/2 = 45,
// C33 = 150, C44 = 80, C55 = C66 = (20 + 30)/2 = 25 GPa; density unchanged;
// thickness = sum.
TEST_F(LayupTest, ZeroNinetyOfTable1EqualsHandAverageExactly) {
  const mat::Material m = layup({{"table1-anisotropic", 0, kH}, {"table1-anisotropic", 90, kH}});
  mat::Matrix6 expected = mat::Matrix6::Zero();
  expected(0, 0) = expected(1, 1) = expected(2, 2) = 150 * GPa;
  expected(0, 1) = expected(1, 0) = 40 * GPa;
  expected(0, 2) = expected(2, 0) = expected(1, 2) = expected(2, 1) = 45 * GPa;
  expected(3, 3) = 80 * GPa;
  expected(4, 4) = expected(5, 5) = 25 * GPa;
  EXPECT_EQ(m.C.matrix(), expected);
  EXPECT_EQ(m.density, mats_.at("table1-anisotropic").density);
  ASSERT_TRUE(m.thickness.has_value());
  EXPECT_EQ(*m.thickness, 2 * kH);
  EXPECT_EQ(m.kind, "layup");
  ASSERT_EQ(m.plies.size(), 2u);
  EXPECT_EQ(m.plies[1].angle_deg, 90);
}

// The same stack with decimal thicknesses (1 mm each): two equal plies weigh
// h_k / h = 1/2 exactly whatever h_k is, so the average is still exact.
TEST_F(LayupTest, ZeroNinetyWithDecimalThicknessIsExactToo) {
  const mat::Material a =
      layup({{"table1-anisotropic", 0, 1e-3}, {"table1-anisotropic", 90, 1e-3}});
  const mat::Material b = layup({{"table1-anisotropic", 0, kH}, {"table1-anisotropic", 90, kH}});
  EXPECT_EQ(a.C.matrix(), b.C.matrix());
  EXPECT_EQ(*a.thickness, 2e-3);
}

// One ply at angle 0 is the ply itself, bit for bit.
TEST_F(LayupTest, SinglePlyEqualsThePly) {
  for (const char* n : {"table1-anisotropic", "aramid"}) {
    const mat::Material m = layup({{n, 0, 3e-4}});
    EXPECT_EQ(m.C.matrix(), mats_.at(n).C.matrix()) << n;
    EXPECT_EQ(m.density, mats_.at(n).density) << n;
    EXPECT_EQ(*m.thickness, 3e-4);
  }
}

// Unequal plies weight by thickness: h_A = h/4, h_B = 3h/4 gives
// D = D_A/4 + 3 D_B/4 and rho = rho_A/4 + 3 rho_B/4 (a handful of roundings:
// 1e-15 relative).
TEST_F(LayupTest, UnequalThicknessesWeightByThickness) {
  const mat::Material m = layup({{"e-glass", 0, kH}, {"vinyl-fabric", 0, 3 * kH}});
  const mat::Material& a = mats_.at("e-glass");
  const mat::Material& b = mats_.at("vinyl-fabric");
  const mat::Matrix6 expected = 0.25 * a.C.matrix() + 0.75 * b.C.matrix();
  EXPECT_LE(relDiff(m.C.matrix(), expected), 1e-15);
  EXPECT_NEAR(m.density, 0.25 * a.density + 0.75 * b.density, 1e-15 * m.density);
  EXPECT_EQ(*m.thickness, 4 * kH);
}

// [0/45/90/-45] of a transversely isotropic ply with its axis in the plane:
// averaging over four angles 45 degrees apart removes the 2nd and 4th angular
// harmonics of the tensor, so the stack is transversely isotropic about z:
// invariant under every rotation about z (rounding of 45-degree rotations:
// 1e-13 relative), while the single ply is not.
TEST_F(LayupTest, QuasiIsotropicStackIsInPlaneIsotropic) {
  const mat::Material m =
      layup({{"aramid", 0, kH}, {"aramid", 45, kH}, {"aramid", 90, kH}, {"aramid", -45, kH}});
  for (double deg : {10.0, 22.5, 30.0, 61.0, 117.0})
    EXPECT_LE(relDiff(m.C.rotatedAboutZ(deg * kPi / 180).matrix(), m.C.matrix()), 1e-13) << deg;
  EXPECT_GT(relDiff(mats_.at("aramid").C.rotatedAboutZ(30 * kPi / 180).matrix(),
                    mats_.at("aramid").C.matrix()),
            0.1);
  const mat::Symmetry s = mat::classify(m.C);
  EXPECT_EQ(s.cls, mat::SymmetryClass::TransverselyIsotropic);
  EXPECT_EQ(s.axis, 2);
  // In-plane isotropy also reads C11 = C22 and C44 = (C11 - C12)/2.
  EXPECT_NEAR(m.C(3, 3), (m.C(0, 0) - m.C(0, 1)) / 2, 1e-13 * m.C(0, 0));
}

// Ply text "MATERIAL:ANGLE_DEG:THICKNESS_M"; the material name may contain ':'.
TEST_F(LayupTest, ParsesPlyText) {
  const mat::Ply p = mat::parsePly("table1-anisotropic:-45:0.00125");
  EXPECT_EQ(p.material, "table1-anisotropic");
  EXPECT_EQ(p.angle_deg, -45);
  EXPECT_EQ(p.thickness, 0.00125);
  EXPECT_EQ(mat::parsePly("lib:cf:30:1e-3").material, "lib:cf");
}

TEST_F(LayupTest, RejectsBadPlies) {
  for (const char* bad : {"aramid:0:0", "aramid:0:-1e-3", "aramid:0", "aramid", "aramid:x:1e-3",
                          "aramid:0:1e-3mm", ":0:1e-3", "aramid:0:nan", "aramid:0:"})
    EXPECT_THROW(mat::parsePly(bad), lamina::Error) << bad;
  // makeLayup checks thickness itself (plies may come from elsewhere than text).
  EXPECT_THROW(layup({{"aramid", 0, 0.0}}), lamina::Error);
  EXPECT_THROW(layup({{"aramid", 0, -kH}}), lamina::Error);
  EXPECT_THROW(layup({}), lamina::Error);
  EXPECT_THROW(layup({{"no-such-material", 0, kH}}), lamina::Error);
}
