// The signed distance and outward normal of each rigid-surface shape at
// points whose distance is known by construction (loads/rigid_surface.hpp),
// and the penalty's bound on the explicit step (loads/contact.hpp).
#include "membrane/loads/contact.hpp"
#include "membrane/loads/rigid_surface.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace lamina::membrane;

namespace {

RigidSurface shape(SurfaceShape s) {
  RigidSurface g;
  g.shape = s;
  g.point = Eigen::Vector3d(1.0, 2.0, 3.0);
  g.axis = Eigen::Vector3d::UnitY();
  g.normal = Eigen::Vector3d::UnitZ();
  g.radius = 2.0;
  g.width = 0.4;
  g.depth = 0.2;
  return g;
}

void expectAt(const RigidSurface& g, const Eigen::Vector3d& x, double gap,
              const Eigen::Vector3d& normal) {
  const Proximity p = g.proximity(x);
  EXPECT_NEAR(p.gap, gap, 1e-12) << x.transpose();
  EXPECT_LT((p.normal - normal).norm(), 1e-12) << x.transpose() << " : " << p.normal.transpose();
}

} // namespace

TEST(RigidSurface, PlaneSphereAndCylinderDistances) {
  const Eigen::Vector3d c(1.0, 2.0, 3.0), z = Eigen::Vector3d::UnitZ();
  expectAt(shape(SurfaceShape::Plane), c + Eigen::Vector3d(5.0, -1.0, 0.25), 0.25, z);
  expectAt(shape(SurfaceShape::Plane), c + Eigen::Vector3d(0.0, 0.0, -0.5), -0.5, z);
  const Eigen::Vector3d d = Eigen::Vector3d(3.0, 0.0, 4.0) / 5.0;
  expectAt(shape(SurfaceShape::Sphere), c + 2.5 * d, 0.5, d);
  expectAt(shape(SurfaceShape::Sphere), c + 1.9 * d, -0.1, d);
  // The cylinder ignores the axial coordinate (axis y).
  expectAt(shape(SurfaceShape::Cylinder), c + 1.5 * d + Eigen::Vector3d(0.0, 7.0, 0.0), -0.5, d);
}

// The arc (axis y, R = 2, width 0.4, depth 0.2): its solid is the rectangle
// |s| <= 0.2, 1.8 <= r <= 2 of the (s, r) half-plane, swept about the axis.
TEST(RigidSurface, ArcIsARingOfRectangularSection) {
  const RigidSurface g = shape(SurfaceShape::Arc);
  const Eigen::Vector3d c = g.point, y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
  expectAt(g, c + Eigen::Vector3d(0.0, 0.1, 2.05), 0.05, z);    // above the top face
  expectAt(g, c + Eigen::Vector3d(0.0, 0.1, 1.97), -0.03, z);   // just under it
  expectAt(g, c + Eigen::Vector3d(0.0, 0.19, 1.9), -0.01, y);   // nearer the side face
  expectAt(g, c + Eigen::Vector3d(0.0, -0.1, 1.82), -0.02, -z); // nearer the inner face
  expectAt(g, c + Eigen::Vector3d(0.0, 0.5, 1.9), 0.3, y);      // beside the beam
  // Beyond the corner (s = 0.2, r = 2): the distance to the corner.
  expectAt(g, c + Eigen::Vector3d(0.0, 0.23, 2.04), 0.05, Eigen::Vector3d(0.0, 0.6, 0.8));
  // Any meridian: the same at 40 degrees round the axis.
  const double a = 40.0 * 3.14159265358979323846 / 180;
  const Eigen::Vector3d radial(std::sin(a), 0.0, std::cos(a));
  expectAt(g, c + 1.97 * radial, -0.03, radial);
  EXPECT_DOUBLE_EQ(g.thickness(), 0.2);
}

// A node of mass m on a fixed surface adds k / m to omega^2; on a free body
// of mass M with N nodes, Gershgorin's rows give 2 k / m and 2 N k / M.
TEST(RigidSurface, PenaltyBoundsTheStep) {
  ContactSurface s;
  s.penalty = 100.0;
  s.nodes = {0, 1};
  const Eigen::VectorXd m = (Eigen::VectorXd(6) << 1, 1, 1, 4, 4, 4).finished();
  EXPECT_DOUBLE_EQ(penaltyOmega2({s}, m), 100.0);
  s.mass = 0.5;
  EXPECT_DOUBLE_EQ(penaltyOmega2({s}, m), 2 * 2 * 100.0 / 0.5);
  s.mass = 0;
  s.damping = 0.75; // sqrt(1 + zeta^2) - zeta = 0.5
  EXPECT_DOUBLE_EQ(penaltyOmega2({s}, m), 400.0);
}
