// The central-difference passes in lanes (the drift and the kick, compiled
// for several vector widths):
// - the kick takes the lanes when the force is external + drag - internal
//   only, and the DOF-by-DOF loop when a spring, damping or contact force is
//   present. A spring on clamped DOFs adds exact zeros to the free DOFs'
//   forces (its own DOFs are then set by their constraint), so the run with
//   it takes the loop and must reach the very numbers of the run without it:
//   both models, with and without pressure and drag (each of the kick's four
//   lane kernels), a moving strike among the constrained DOFs;
// - the drift gives u_{n+1} = u_n + dt (v_n + dt/2 a_n) of every free DOF
//   bit for bit, written out here DOF by DOF;
// - a state that overflows is caught in the lanes (the constrained DOFs'
//   corrections of the count do not hide it): DivergenceError at the step.
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace lamina::membrane;

namespace {

/// Steps @p text 40 times; @return the final u, v and a, one after another.
Eigen::VectorXd finalState(const std::string& text) {
  const Model model = test::modelFromText(text); // the simulation keeps a reference
  Simulation sim(model);
  for (int n = 0; n < 40; ++n)
    sim.step();
  Eigen::VectorXd s(3 * sim.u().size());
  s << sim.u(), sim.v(), sim.a();
  return s;
}

/// @return an 8 x 8 sheet of @p model ("" linear) stepped explicitly at
/// 2e-6 s, its left edge clamped, its centre struck at @p speed, then @p extra
std::string clampedSheet(const std::string& model, const char* speed, const std::string& extra) {
  return model + test::isotropicSquare(8) +
         "[time]\nintegrator = \"explicit\"\ndt = 2.0e-6\nt_end = 1.0\n"
         "[[fixed]]\nnodes = \"left\"\n[[strike]]\nat = [0.5, 0.5]\nspeed = " +
         speed + "\n" + extra;
}

const char* const kModels[] = {"", "model = \"large_deflection\"\n"};

const char* const kPressure = "[[load]]\ntype = \"pressure\"\nvalue = 3000.0\nprofile = \"pulse\"\n"
                              "duration = 2.0e-4\n";
const char* const kDrag = "[[drag]]\ncd = 1.5\n";
const char* const kSpringOnClamp = "[[spring]]\nnodes = \"left\"\ncomponents = \"z\"\n"
                                   "stiffness = 1.0e4\n";
} // namespace

TEST(CentralDifferenceLanes, GiveTheBitsOfTheLoopOverDofs) {
  for (const std::string model : kModels)
    for (int loads = 0; loads < 4; ++loads) {
      const std::string text = clampedSheet(
          model, "1.0", std::string((loads & 1) ? kPressure : "") + ((loads & 2) ? kDrag : ""));
      const Eigen::VectorXd lanes = finalState(text);
      const Eigen::VectorXd loop = finalState(text + kSpringOnClamp);
      ASSERT_EQ(lanes.size(), loop.size());
      EXPECT_GT(lanes.cwiseAbs().maxCoeff(), 0.0); // the strike moved the sheet
      Eigen::Index differ = 0;
      for (Eigen::Index i = 0; i < lanes.size(); ++i)
        differ += !(lanes[i] == loop[i]); // == : +0 and -0 are the same number
      EXPECT_EQ(differ, 0) << model << "loads " << loads;
    }
}

TEST(CentralDifferenceLanes, DriftIsTheUpdateOfEachDof) {
  for (const std::string model : kModels) {
    const Model m = test::modelFromText(clampedSheet(model, "1.0", kPressure));
    Simulation sim(m);
    const double dt = 2.0e-6, h = 0.5 * dt;
    const std::vector<char>& fixed = sim.system().constraints().mask();
    for (int n = 0; n < 30; ++n) {
      const Eigen::VectorXd u = sim.u(), v = sim.v(), a = sim.a();
      sim.step();
      Eigen::Index differ = 0;
      for (Eigen::Index i = 0; i < u.size(); ++i) {
        const double vh = v[i] + h * a[i];
        differ += !fixed[i] && !(sim.u()[i] == u[i] + dt * vh);
      }
      ASSERT_EQ(differ, 0) << model << "step " << n;
    }
  }
}

TEST(CentralDifferenceLanes, OverflowIsCaughtAtItsStep) {
  // A strike at 1e306 m/s: the struck node's neighbours take forces that
  // overflow their accelerations within a few steps.
  for (const std::string model : kModels) {
    const Model m = test::modelFromText(clampedSheet(model, "1.0e306", ""));
    Simulation sim(m);
    std::string message;
    try {
      for (int n = 0; n < 20; ++n)
        sim.step();
    } catch (const lamina::DivergenceError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("non-finite state"), std::string::npos) << model << message;
  }
}
