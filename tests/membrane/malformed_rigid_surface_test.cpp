// [[rigid_surface]] input that cannot describe a rigid body, or that a run
// could not honour, is refused with an error naming the key: a radius,
// width or depth <= 0, a NaN or infinite position, an axis or normal of zero
// length, a friction coefficient below 0, a penalty <= 0, an unknown shape
// (the message lists the valid ones), a key of another shape, a mass on a
// shape that cannot be a free body, and contact under the Newmark scheme.
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace lamina::membrane;

namespace {

/// An explicit large-deflection square with one rigid surface of @p keys.
std::string withSurface(const std::string& keys, const std::string& time = "") {
  return "model = \"large_deflection\"\n" + test::isotropicSquare(4) +
         (time.empty() ? "[time]\nintegrator = \"explicit\"\nt_end = 1.0e-4\n" : time) +
         "[[fixed]]\nnodes = \"edges\"\n[[rigid_surface]]\nname = \"beam\"\n" + keys;
}

const std::string kArc = "shape = \"arc\"\ncenter = [0.5, 0.0, -12.0]\naxis = [1.0, 0.0, 0.0]\n"
                         "radius = 12.0\nwidth = 0.1\npenalty = 1.0e4\n";
const std::string kSphere = "shape = \"sphere\"\ncenter = [0.5, 0.5, 0.2]\nradius = 0.1\n"
                            "penalty = 1.0e4\n";

/// Expects case @p text to be refused naming each of @p parts.
void expectRefused(const std::string& text, const std::vector<std::string>& parts) {
  test::expectHas(test::buildError(withSurface(text)), parts);
}

/// @return @p base with the line starting "key =" replaced by @p line
std::string replaced(std::string base, const std::string& key, const std::string& line) {
  const auto at = base.find(key + " =");
  const auto end = base.find('\n', at);
  return base.replace(at, end - at, line);
}

} // namespace

TEST(MalformedRigidSurface, GoodSurfacesBuild) {
  EXPECT_EQ(test::buildError(withSurface(kArc)), "");
  EXPECT_EQ(test::buildError(withSurface(kSphere + "mass = 0.1\nfriction = 0.3\n")), "");
  EXPECT_EQ(test::buildError(withSurface("shape = \"plane\"\npoint = [0.0, 0.0, -0.1]\n"
                                         "normal = [0.0, 0.0, 2.0]\npenalty = 10.0\n")),
            "");
}

TEST(MalformedRigidSurface, NonPositiveSizesAreRefusedNamingTheKey) {
  for (const char* v : {"0.0", "-1.0"}) {
    expectRefused(replaced(kArc, "radius", std::string("radius = ") + v),
                  {"rigid_surface", "radius", "> 0"});
    expectRefused(replaced(kArc, "width", std::string("width = ") + v),
                  {"rigid_surface", "width", "> 0"});
    expectRefused(kArc + "depth = " + v + "\n", {"rigid_surface", "depth", "> 0"});
    expectRefused(replaced(kSphere, "radius", std::string("radius = ") + v), {"radius", "> 0"});
    expectRefused(replaced(kSphere, "penalty", std::string("penalty = ") + v), {"penalty", "> 0"});
  }
  expectRefused(kArc + "depth = 13.0\n", {"depth", "exceeds the radius"});
}

TEST(MalformedRigidSurface, NanOrInfinitePositionsAreRefused) {
  expectRefused(replaced(kArc, "center", "center = [nan, 0.0, -12.0]"), {"center"});
  expectRefused(replaced(kSphere, "center", "center = [0.5, inf, 0.2]"), {"center"});
  expectRefused(replaced(kSphere, "center", "center = [0.5, 0.2]"), {"center", "[x, y, z]"});
  expectRefused("shape = \"plane\"\npoint = [0.0, -inf, 0.0]\nnormal = [0.0, 0.0, 1.0]\n"
                "penalty = 10.0\n",
                {"point"});
  expectRefused(kSphere + "velocity = [0.0, nan, 0.0]\n", {"velocity"});
}

TEST(MalformedRigidSurface, ZeroDirectionsAreRefused) {
  expectRefused(replaced(kArc, "axis", "axis = [0.0, 0.0, 0.0]"), {"axis", "non-zero length"});
  expectRefused("shape = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 0.0]\n"
                "penalty = 10.0\n",
                {"normal", "non-zero length"});
}

TEST(MalformedRigidSurface, FrictionAndDampingOutOfRangeAreRefused) {
  expectRefused(kSphere + "friction = -0.1\n", {"friction", ">= 0"});
  expectRefused(kSphere + "slip_velocity = 0.01\n", {"slip_velocity", "friction > 0"});
  expectRefused(kSphere + "friction = 0.2\nslip_velocity = 0.0\n", {"slip_velocity", "> 0"});
  expectRefused(kSphere + "contact_damping = 1.0\n", {"contact_damping", "[0, 1)"});
  expectRefused(kSphere + "penetration_tolerance = 0.0\n", {"penetration_tolerance", "> 0"});
}

TEST(MalformedRigidSurface, UnknownShapeListsTheShapes) {
  expectRefused(replaced(kSphere, "shape", "shape = \"cube\""),
                {"shape", "cube", "\"cylinder\"", "\"arc\"", "\"plane\"", "\"sphere\""});
}

TEST(MalformedRigidSurface, KeysOfAnotherShapeOrAFreeNonSphereAreRefused) {
  expectRefused(kSphere + "width = 0.1\n", {"width", "does not apply", "sphere"});
  expectRefused(kArc + "mass = 1.0\n", {"mass", "only a sphere"});
  expectRefused(kSphere + "mass = 0.0\n", {"mass", "> 0"});
}

TEST(MalformedRigidSurface, ContactUnderNewmarkIsRefused) {
  const std::string text = test::isotropicSquare(4) +
                           "[time]\ndt = 1.0e-5\nt_end = 1.0e-4\n[[fixed]]\nnodes = \"edges\"\n"
                           "[[rigid_surface]]\n" +
                           kSphere;
  test::expectHas(test::buildError(text),
                  {"rigid_surface", "needs time.integrator = \"explicit\""});
}

TEST(MalformedRigidSurface, NamesMustBeUnique) {
  expectRefused(kSphere + "[[rigid_surface]]\nname = \"beam\"\n" + kArc, {"name", "beam"});
  expectRefused(kSphere + "[[spring]]\nname = \"beam\"\nnodes = \"edges\"\nstiffness = 1.0\n",
                {"name", "beam"});
}
