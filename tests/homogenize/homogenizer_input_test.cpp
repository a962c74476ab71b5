// Bad input to the Homogenizer is named: the first phase stiffness that is
// not positive definite among many (as with composite voxels, whose
// stiffnesses are checked on the threads) and a voxel whose phase index has
// no stiffness.

#include "core/error.hpp"
#include "homogenize/homogenizer.hpp"

#include <gtest/gtest.h>

#include <string>

namespace lamina::test {
namespace {

using materials::Stiffness;

homogenize::Grid grid8() {
  homogenize::Grid g;
  g.n = {8, 8, 8};
  g.h = {0.125, 0.125, 0.125};
  return g;
}

// @return the message of the Error that @p fn throws ("" if none)
template <class F>
std::string errorOf(F&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(HomogenizerInput, FirstIndefinitePhaseIsNamed) {
  // 1000 valid phases with two indefinite ones (a negative shear modulus):
  // the lower index is reported
  std::vector<Stiffness> C(1000, Stiffness::isotropic(156e6, 0.494));
  materials::Matrix6 bad = C[0].matrix();
  bad(3, 3) = -1e6;
  C[731] = Stiffness(bad);
  C[412] = Stiffness(bad);
  std::vector<std::int32_t> phase(grid8().size(), 0);
  const std::string msg = errorOf([&] {
    homogenize::Homogenizer h(grid8(), phase, C, std::vector<double>(C.size(), 1000.0), {});
  });
  EXPECT_NE(msg.find("phase 412"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not positive definite"), std::string::npos) << msg;
}

TEST(HomogenizerInput, PhaseIndexWithoutStiffnessIsNamed) {
  std::vector<Stiffness> C(2, Stiffness::isotropic(156e6, 0.494));
  std::vector<std::int32_t> phase(grid8().size(), 0);
  phase[300] = 7;
  phase[100] = 5;
  homogenize::Homogenizer h(grid8(), phase, C, {1000.0, 1000.0}, {});
  const std::string msg = errorOf([&] { h.run(); });
  EXPECT_NE(msg.find("phase index 5 has no stiffness"), std::string::npos) << msg;
}

} // namespace
} // namespace lamina::test
