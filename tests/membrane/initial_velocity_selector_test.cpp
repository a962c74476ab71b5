// [initial] with a node selector: the velocity goes to the selected nodes
// only (a projectile's patch), every node without a selector (as before),
// and a projectile (point mass + initial velocity on one patch) carries the
// momentum of its mass and of the sheet under it, which the free sheet then
// conserves.
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace lamina::membrane;

namespace {

constexpr double kPi = 3.14159265358979323846; // as the case reader's

/// A free 1 m square of 8 x 8 squares (node spacing 0.125 m) on the
/// large-deflection model, explicit, with @p extra tables appended.
Model freeSquare(const std::string& extra) {
  return test::modelFromText("model = \"large_deflection\"\n" + test::isotropicSquare(8) +
                             "[time]\nintegrator = \"explicit\"\nsafety = 0.5\nt_end = 1.0e-4\n" +
                             extra);
}

/// The central patch of the tests: x, y in [0.375, 0.625], i.e. the 3 x 3
/// nodes at 0.375, 0.5, 0.625 of the 0.125 m grid.
bool inPatch(const Eigen::Vector2d& p) {
  auto in = [](double s) { return s >= 0.375 - 1e-12 && s <= 0.625 + 1e-12; };
  return in(p.x()) && in(p.y());
}

} // namespace

// Without a selector every node gets the velocity, exactly (today's meaning),
// and the sine mode is the formula over the bounding box.
TEST(InitialVelocitySelector, WithoutSelectorEveryNodeMoves) {
  const Model m = freeSquare("[initial]\nvelocity = [0.25, -0.5, 3.0]\nmode = [1, 2]\n"
                             "mode_velocity = 2.0\n");
  ASSERT_EQ(m.v0.size(), 3 * m.mesh.numNodes());
  for (int i = 0; i < m.mesh.numNodes(); ++i) {
    const double x = m.mesh.nodes[i].x(), y = m.mesh.nodes[i].y();
    EXPECT_EQ(m.v0[3 * i], 0.25);
    EXPECT_EQ(m.v0[3 * i + 1], -0.5);
    // The same expression as the reader evaluates: equal to the last bit.
    EXPECT_EQ(m.v0[3 * i + 2], 3.0 + 2.0 * std::sin(1.0 * kPi * x) *
                                         std::sin(2.0 * kPi * y));
  }
}

// A box gives the velocity to the 9 nodes inside it (counted here from the
// coordinates), `at` to the one node there, `all = true` to every node.
TEST(InitialVelocitySelector, BoxAtAndAllSelectTheirNodes) {
  const Model box = freeSquare("[initial]\nvelocity = [0.0, 0.0, -50.0]\n"
                               "box = [0.375, 0.625, 0.375, 0.625]\n");
  int moving = 0;
  for (int i = 0; i < box.mesh.numNodes(); ++i) {
    const bool in = inPatch(box.mesh.nodes[i]);
    EXPECT_EQ(box.v0[3 * i + 2], in ? -50.0 : 0.0) << "node " << i;
    EXPECT_EQ(box.v0[3 * i], 0.0);
    moving += in;
  }
  EXPECT_EQ(moving, 9);

  const Model at = freeSquare("[initial]\nvelocity = [0.0, 0.0, 7.0]\nat = [0.5, 0.5]\n");
  for (int i = 0; i < at.mesh.numNodes(); ++i) {
    const bool centre = (at.mesh.nodes[i] - Eigen::Vector2d(0.5, 0.5)).norm() < 1e-12;
    EXPECT_EQ(at.v0[3 * i + 2], centre ? 7.0 : 0.0) << "node " << i;
  }

  const Model all = freeSquare("[initial]\nvelocity = [1.0, 2.0, 3.0]\nall = true\n");
  const Model none = freeSquare("[initial]\nvelocity = [1.0, 2.0, 3.0]\n");
  EXPECT_EQ(all.v0, none.v0);
}

// A projectile of mass M on the patch, both moving at V: the initial
// momentum is V (M + the sheet's lumped mass of the patch nodes, rho h A / 3
// per triangle corner, summed here from the mesh), and the free sheet keeps
// its total momentum (no external force: exact up to round-off, 1e-12 of
// the initial value over 200 steps).
TEST(InitialVelocitySelector, ProjectilePatchCarriesAndConservesItsMomentum) {
  const double M = 0.02, V = -5.0, rho_h = 1000.0 * 1.0e-3;
  const Model m = freeSquare("[[point_mass]]\nmass = 0.02\nbox = [0.375, 0.625, 0.375, 0.625]\n"
                             "[initial]\nvelocity = [0.0, 0.0, -5.0]\n"
                             "box = [0.375, 0.625, 0.375, 0.625]\n");
  double sheet = 0;
  for (const auto& t : m.mesh.triangles) {
    const Eigen::Vector2d a = m.mesh.nodes[t[0]], b = m.mesh.nodes[t[1]], c = m.mesh.nodes[t[2]];
    const double area = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    for (int k = 0; k < 3; ++k)
      if (inPatch(m.mesh.nodes[t[k]]))
        sheet += rho_h * area / 3;
  }
  Simulation sim(m);
  auto momentumZ = [&] {
    const Eigen::VectorXd p = sim.M() * sim.v();
    double pz = 0;
    for (int i = 0; i < m.mesh.numNodes(); ++i)
      pz += p[3 * i + 2];
    return pz;
  };
  const double p0 = V * (M + sheet);
  EXPECT_NEAR(momentumZ(), p0, 1e-14 * std::abs(p0));
  for (int s = 0; s < 200; ++s)
    sim.step();
  EXPECT_NEAR(momentumZ(), p0, 1e-12 * std::abs(p0));
}
