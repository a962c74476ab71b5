// The second-order system both integrators step (SecondOrderSystem), and the
// one pressure load of both models (ElementPressure with its Geometry flag):
// - the reactions the system gives close the momentum balance of every step,
//   sum(M a) = sum(F_ext + F_drag + F_s + F_damp + F_c) + sum(R) (the internal
//   forces sum to zero: a translation strains nothing), for Newmark and for
//   central differences, with pressure, drag, springs, damping and a rigid set;
// - a uniform pressure on the reference geometry (a fixed pattern) and on the
//   current one (the element loop) are the same force on the flat membrane,
//   p A e_z in total; on a turned membrane the current one turns, the
//   reference one does not; so for a blast;
// - a blast on the linear model (reference geometry) gives a free panel the
//   table's impulse times its area as momentum.
#include "helpers.hpp"

#include "membrane/loads/blast_pressure.hpp"
#include "membrane/loads/element_pressure.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace lamina::membrane;

namespace {

/// The z components summed.
double sumZ(const Eigen::VectorXd& f) {
  double s = 0;
  for (Eigen::Index i = 2; i < f.size(); i += 3)
    s += f[i];
  return s;
}

/// Runs @p text and returns the largest |sum_z(M a) - sum_z(F) - sum_z(R)|
/// over its steps; @p scale is the largest sum of the magnitudes of the
/// terms (|m a|, every force, the internal force where the scheme keeps it).
double worstMomentumResidual(const std::string& text, double& scale) {
  Model m = test::modelFromText(text);
  Simulation sim(m);
  const SecondOrderSystem& sys = sim.system();
  const Eigen::VectorXd& lumped = sys.lumpedMass(); // sum(M a) = sum(m a): M is symmetric
  double worst = 0;
  scale = 0;
  for (int n = 0; n < 60; ++n) {
    sim.step();
    const StateForces& f = sim.integrator().forces();
    const Eigen::VectorXd ma = lumped.cwiseProduct(sim.a());
    double forces = sumZ(f.external) + sumZ(f.drag);
    double size = ma.cwiseAbs().sum() + f.external.cwiseAbs().sum() + f.drag.cwiseAbs().sum();
    for (const Eigen::VectorXd* g : {&f.spring, &f.damping, &f.contact.force, &f.internal})
      if (g->size()) {
        forces += g == &f.internal ? 0.0 : sumZ(*g);
        size += g->cwiseAbs().sum();
      }
    double reactions = 0;
    for (const Eigen::Vector3d& r : sys.constraints().sums(f.reaction))
      reactions += r.z();
    worst = std::max(worst, std::abs(sumZ(ma) - forces - reactions));
    scale = std::max(scale, size);
  }
  return worst;
}

/// The loads of the momentum tests: a pressure pulse, drag, springs on the
/// right edge tied into a rigid set, the left edge clamped, the centre
/// struck at 1 m/s on a spring (a spring on a constrained, moving DOF: its
/// force enters the reaction there).
const std::string kLoads = R"([[fixed]]
nodes = "left"
[[load]]
type = "pressure"
value = 3000.0
profile = "pulse"
duration = 2.0e-4
[[drag]]
cd = 1.5
)" + test::rigidOnSprings("right", 1.0e4) +
                           R"([[strike]]
at = [0.5, 0.5]
speed = 1.0
[[spring]]
at = [0.5, 0.5]
components = "z"
stiffness = 1.0e5
)";

/// Expects the momentum balance of every step of @p text to close.
/// Round-off bound: each sum adds ~250 terms, so 1e-12 of the summed
/// magnitudes is far above the rounding (~250 x 1e-16) and far below any
/// missing force (the pressure alone is 3000 N on the panel). Newmark solves
/// with Cholesky: a CG residual (1e-10) would enter the balance.
void expectMomentumBalance(const std::string& text) {
  double scale = 0;
  const double worst = worstMomentumResidual(text, scale);
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-12 * scale) << "scale " << scale;
}
} // namespace

TEST(SecondOrderSystem, ReactionsCloseTheMomentumBalanceOfNewmark) {
  expectMomentumBalance(test::isotropicSquare(8) +
                        "[time]\ndt = 2.0e-5\nt_end = 1.0\n[solver]\ntype = \"cholesky\"\n" +
                        kLoads);
}

TEST(SecondOrderSystem, ReactionsCloseTheMomentumBalanceOfCentralDifferences) {
  expectMomentumBalance(
      test::isotropicSquare(8) +
      "[time]\nintegrator = \"explicit\"\ndt = 2.0e-5\nt_end = 1.0\ndamping = 50.0\n" + kLoads);
}

TEST(SecondOrderSystem, ReactionsCloseTheMomentumBalanceOfTheLargeDeflectionModel) {
  expectMomentumBalance("model = \"large_deflection\"\n" + test::isotropicSquare(8) +
                        "[time]\nsafety = 0.5\nt_end = 1.0\ndamping = 50.0\n" + kLoads);
}

namespace {
/// A flat mesh of the unit square, 4 x 4 squares.
Mesh flatSquare() {
  Model m = test::modelFromText(test::isotropicSquare(4) + "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n");
  return m.mesh;
}

std::vector<int> allElements(const Mesh& mesh) {
  std::vector<int> e(static_cast<size_t>(mesh.numElements()));
  for (int i = 0; i < mesh.numElements(); ++i)
    e[static_cast<size_t>(i)] = i;
  return e;
}

Eigen::VectorXd forceOf(const SurfaceLoad& load, const Mesh& mesh, const Eigen::VectorXd& u,
                        double t) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  load.add(t, mesh, u, Eigen::VectorXd(), f);
  return f;
}

Eigen::Vector3d total(const Eigen::VectorXd& f) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < f.size(); i += 3)
    s += f.segment<3>(i);
  return s;
}

/// Displacements that turn the unit square rigidly by 90 degrees about the x axis (z = y).
Eigen::VectorXd turnedAboutX(const Mesh& mesh) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  for (int i = 0; i < mesh.numNodes(); ++i) {
    const Eigen::Vector3d X = mesh.point(i);
    u.segment<3>(3 * i) = Eigen::Vector3d(X.x(), -X.z(), X.y()) - X;
  }
  return u;
}
} // namespace

// The two geometries of one pressure on the flat membrane at rest: the
// pattern (edge-midpoint rule on the reference areas) and the element loop
// (p A n / 3 from the cross product) round differently, nothing else: 1e-14
// of the largest nodal force. In total p A e_z (A = 1 m^2).
TEST(SecondOrderSystem, OnePressureOnBothGeometries) {
  const Mesh mesh = flatSquare();
  const double p = 2500.0;
  const UniformPressure ref("p", mesh, allElements(mesh), p, TimeProfile{}, Geometry::Reference);
  const UniformPressure cur("p", mesh, allElements(mesh), p, TimeProfile{}, Geometry::Current);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  const Eigen::VectorXd fr = forceOf(ref, mesh, zero, 0.0), fc = forceOf(cur, mesh, zero, 0.0);
  EXPECT_LT((fr - fc).cwiseAbs().maxCoeff(), 1e-14 * fr.cwiseAbs().maxCoeff());
  EXPECT_NEAR(total(fr).z(), p, 1e-12 * p);
  EXPECT_EQ(total(fr).head<2>().norm(), 0.0);
  // Turned by 90 degrees about x: the current normal is e_z x ... = -e_y, the
  // reference one stays e_z (the linear model's small displacements).
  const Eigen::VectorXd u = turnedAboutX(mesh);
  const Eigen::Vector3d tc = total(forceOf(cur, mesh, u, 0.0));
  const Eigen::Vector3d tr = total(forceOf(ref, mesh, u, 0.0));
  EXPECT_NEAR(tc.y(), -p, 1e-12 * p);
  EXPECT_NEAR(tc.x(), 0.0, 1e-12 * p);
  EXPECT_NEAR(tc.z(), 0.0, 1e-12 * p);
  EXPECT_EQ(tr, total(fr));
}

// A blast on both geometries: at rest the same force (1e-14, the rounding
// of the two area vectors); turned, the current one follows the element.
TEST(SecondOrderSystem, OneBlastOnBothGeometries) {
  const Mesh mesh = flatSquare();
  BlastCharge c;
  c.mass = 1.0;
  c.position = Eigen::Vector3d(0.5, 0.5, -3.0);
  const BlastPressure ref("b", allElements(mesh), mesh, c, Geometry::Reference);
  const BlastPressure cur("b", allElements(mesh), mesh, c, Geometry::Current);
  const double t = ref.firstArrival() + 1e-5;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3 * mesh.numNodes());
  const Eigen::VectorXd fr = forceOf(ref, mesh, zero, t), fc = forceOf(cur, mesh, zero, t);
  ASSERT_GT(total(fr).z(), 0.0); // pushed away from the charge below
  EXPECT_LT((fr - fc).cwiseAbs().maxCoeff(), 1e-14 * fr.cwiseAbs().maxCoeff());
  const Eigen::VectorXd u = turnedAboutX(mesh);
  EXPECT_EQ(total(forceOf(ref, mesh, u, t)), total(fr));
  EXPECT_GT(total(forceOf(cur, mesh, u, t)).cwiseAbs().head<2>().norm(), 0.0);
}

// A pressure table on the linear model's free panel: Newmark's trapezoidal
// velocity update sums the steps' interval means, which together are the
// table's impulse (0.5 x 3e-4 s x 1000 Pa = 0.15 Pa s), so the panel's
// momentum sum(M v)_z after the pulse is 0.15 N s on its 1 m^2 (round-off
// of 100 steps: 1e-12), whatever the step.
TEST(SecondOrderSystem, BlastOnTheLinearModelGivesTheTablesImpulse) {
  const auto csv = test::tempPath("linear-blast-table.csv");
  std::ofstream(csv) << "# t (s), p (Pa)\n0.0, 0.0\n1.0e-4, 1000.0\n3.0e-4, 0.0\n";
  const double dt = 7.0e-6; // not a divisor of the table's breakpoints
  Model m = test::modelFromText(
      test::isotropicSquare(6) + "[time]\ndt = " + lamina::core::formatExact(dt) +
      "\nt_end = 1.0\n[solver]\ntype = \"cholesky\"\n[[blast]]\ntable = \"" + csv.string() +
      "\"\n");
  Simulation sim(m);
  while (sim.time() < 4.0e-4)
    sim.step();
  Eigen::VectorXd mv;
  multiply(sim.M(), sim.v(), mv);
  EXPECT_NEAR(sumZ(mv), 0.15, 1e-12 * 0.15);
  std::filesystem::remove(csv);
}
