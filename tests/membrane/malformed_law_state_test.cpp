// A section's law whose state goes non-finite mid-run: the run stops with an
// error naming the element and the time, and its outputs are closed and
// readable (summary.json records the divergence, energy.csv ends in a whole row).
#include "restart_helpers.hpp"

#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace lamina::membrane {
namespace {

/// Linear isotropic stress, but NaN from the @p bad-th update of a point on
/// (its state counts the updates): a law that breaks down mid-run.
class BreaksDownLaw final : public materials::ConstitutiveLaw {
public:
  explicit BreaksDownLaw(int bad) : C_(materials::Stiffness::isotropic(1e9, 0.3)), bad_(bad) {}
  materials::LawKind kind() const override { return materials::LawKind::Gvbo; }
  bool isLinear() const override { return false; }
  int stateSize() const override { return 1; }
  void initState(double* state) const override { state[0] = 0; }
  materials::Stiffness elasticStiffness(double = 1.0) const override { return C_; }
  void update(const materials::PointStep& step, const double* state_n, double* state,
              materials::Vector6& sigma, materials::Matrix6* tangent) const override {
    state[0] = state_n[0] + (step.dt > 0 ? 1 : 0);
    sigma = C_.matrix() * step.eps;
    if (state[0] >= bad_)
      sigma[0] = std::numeric_limits<double>::quiet_NaN();
    if (tangent)
      *tangent = C_.matrix();
  }

private:
  materials::Stiffness C_;
  int bad_;
};

TEST(MalformedLawState, NonFiniteStressStopsNamingElementAndTimeWithReadableOutputs) {
  Model m = test::modelFromText(R"(
model = "large_deflection"
[mesh]
Lx = 1.0
nx = 4
[[section]]
E = 1.0e9
nu = 0.3
density = 1000.0
thickness = 1.0e-3
[time]
integrator = "explicit"
dt = 1.0e-5
t_end = 1.0e-3
[[fixed]]
nodes = "edges"
[initial]
velocity = [0.0, 0.0, 1.0]
)");
  m.sections[0].law = std::make_shared<BreaksDownLaw>(20);
  m.sections[0].material = "breaks-down";
  const test::Folder dir("law-state-nan");
  RunOptions o;
  o.out_dir = dir.path;
  o.quiet = true;
  try {
    runModel(m, o);
    FAIL() << "a non-finite law state must stop the run";
  } catch (const DivergenceError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("element "), std::string::npos) << msg;
    EXPECT_NE(msg.find("breaks-down"), std::string::npos) << msg;
    EXPECT_NE(msg.find("t = 0.0002"), std::string::npos) << msg; // step 20 of 1e-5 s
  }
  const std::string summary = test::slurp(dir.path / "summary.json");
  EXPECT_NE(summary.find("\"diverged\""), std::string::npos);
  const std::string energy = test::slurp(dir.path / "energy.csv");
  ASSERT_FALSE(energy.empty());
  EXPECT_EQ(energy.back(), '\n'); // whole rows only
  EXPECT_NE(energy.find("inelastic_dissipation"), std::string::npos);
}

} // namespace
} // namespace lamina::membrane
