// The contract of planeStressUpdate (materials/plane_stress.hpp): the state
// may alias the state at t_n (same result to the bit); bad steps are refused
// with a message that says what is wrong; a step that cannot converge gives
// the residual.

#include "core/error.hpp"
#include "materials/catalog.hpp"
#include "materials/gvbo_law.hpp"
#include "materials/plane_stress.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace mat = lamina::materials;

namespace {

mat::GvboLaw polyurea() {
  static const mat::Catalog cat;
  return mat::GvboLaw(*cat.get("polyurea-gvbo").gvbo);
}

std::string errorOf(const mat::ConstitutiveLaw& law, const mat::PlaneStressStep& s,
                    double tolerance = mat::kPlaneStressTolerance) {
  std::vector<double> st(static_cast<std::size_t>(law.stateSize()));
  law.initState(st.data());
  try {
    mat::planeStressUpdate(law, s, st.data(), st.data(), false, tolerance);
  } catch (const lamina::Error& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST(PlaneStressContract, StateMayAliasStateN) {
  const mat::GvboLaw law = polyurea();
  std::vector<double> a(mat::GvboState::kSize), b(mat::GvboState::kSize), c;
  law.initState(a.data());
  c = a;
  mat::PlaneStressStep s;
  s.deps_p << 3e-3, 1e-3, 2e-3;
  s.J2 = (1 + 3e-3) * (1 + 1e-3);
  s.dt = 1e-4;
  const auto r1 = mat::planeStressUpdate(law, s, a.data(), b.data(), true);
  const auto r2 = mat::planeStressUpdate(law, s, c.data(), c.data(), true);
  EXPECT_EQ(b, c);
  EXPECT_EQ(r1.sigma, r2.sigma);
  EXPECT_EQ(r1.tangent, r2.tangent);
  EXPECT_EQ(r1.iterations, r2.iterations);
}

TEST(PlaneStressContract, BadStepsAreRefused) {
  const mat::GvboLaw law = polyurea();
  mat::PlaneStressStep s;
  s.n_free = 4;
  EXPECT_NE(errorOf(law, s).find("4 free directions"), std::string::npos) << errorOf(law, s);
  s.n_free = 2;
  s.free_dir = {Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(2, 2, 0), Eigen::Vector3d::Zero()};
  EXPECT_NE(errorOf(law, s).find("linearly dependent"), std::string::npos) << errorOf(law, s);
  s.free_dir[1] = Eigen::Vector3d::Zero();
  EXPECT_NE(errorOf(law, s).find("free direction 2 is zero"), std::string::npos);
  s.n_free = 0;
  s.lambda3_n = 0;
  EXPECT_NE(errorOf(law, s).find("must be positive"), std::string::npos);
  s.lambda3_n = 1;
  s.J2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(errorOf(law, s).find("must be positive"), std::string::npos);
}

// A tolerance below round-off cannot be met: the step is refused after the
// cap, and the message gives the residual and the iterations.
TEST(PlaneStressContract, NoConvergenceGivesTheResidual) {
  const mat::GvboLaw law = polyurea();
  mat::PlaneStressStep s;
  s.deps_p << 3e-2, 1e-2, 0;
  s.J2 = 1.03 * 1.01;
  s.dt = 1e-4;
  const std::string msg = errorOf(law, s, 1e-30);
  EXPECT_NE(msg.find("did not vanish: residual"), std::string::npos) << msg;
  EXPECT_NE(msg.find("after 50 iterations"), std::string::npos) << msg;
}
