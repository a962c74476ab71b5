/// @file case_contact.cpp
/// @brief [[rigid_surface]] of a case: rigid bodies the membrane rests on
/// (loads/rigid_surface.hpp for the shapes, loads/contact.hpp for the
/// penalty contact).

#include "membrane/io/case_builders.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "membrane/loads/contact.hpp"

#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace lamina::membrane::case_io {

namespace {

/// The keys of a shape's geometry; a key of another shape is refused.
constexpr const char* kGeometryKeys[] = {"center", "point", "axis", "normal",
                                         "radius", "width", "depth"};

/// @return whether @p key describes the geometry of @p shape
bool geometryKeyOf(SurfaceShape shape, std::string_view key) {
  switch (shape) {
  case SurfaceShape::Plane:
    return key == "point" || key == "normal";
  case SurfaceShape::Sphere:
    return key == "center" || key == "radius";
  case SurfaceShape::Cylinder:
    return key == "center" || key == "axis" || key == "radius";
  case SurfaceShape::Arc:
    return key == "center" || key == "axis" || key == "radius" || key == "width" || key == "depth";
  }
  return false;
}

/// @return the 3-vector at @p key of @p r (finite: the reader refuses nan and inf)
Eigen::Vector3d readVector(const core::TableReader& r, const std::string& key,
                           const char* meaning) {
  const auto v = r.getDoubleArray(key);
  if (v.size() != 3)
    r.fail(key, std::string("expected ") + meaning);
  return {v[0], v[1], v[2]};
}

/// @return the unit vector along the 3-vector at @p key (refused when zero)
Eigen::Vector3d readUnit(const core::TableReader& r, const std::string& key) {
  const Eigen::Vector3d d = readVector(r, key, "[x, y, z] (a direction)");
  if (!(d.norm() > 0) || !std::isfinite(d.norm()))
    r.fail(key, key + " must have a non-zero length");
  return d.normalized();
}

/// @return the length at @p key, which must be > 0 (m)
double readLength(const core::TableReader& r, const std::string& key) {
  const double x = r.getDouble(key);
  if (!(x > 0))
    r.fail(key, key + " must be > 0 (m), got " + core::formatShort(x));
  return x;
}

/// The geometry keys of @p r for its shape.
RigidSurface readGeometry(const core::TableReader& r) {
  RigidSurface g;
  g.shape = r.getChoice("shape", kSurfaceShapeNames);
  const std::string shape(kSurfaceShapeNames.name(g.shape));
  for (const char* key : kGeometryKeys)
    if (r.has(key) && !geometryKeyOf(g.shape, key))
      r.fail(key, std::string(key) + " does not apply to shape \"" + shape + "\"");
  if (g.shape == SurfaceShape::Plane) {
    g.point = readVector(r, "point", "[x, y, z] (m)");
    g.normal = readUnit(r, "normal");
    return g;
  }
  g.point = readVector(r, "center", "[x, y, z] (m)");
  g.radius = readLength(r, "radius");
  if (g.shape == SurfaceShape::Sphere)
    return g;
  g.axis = readUnit(r, "axis");
  if (g.shape == SurfaceShape::Arc) {
    g.width = readLength(r, "width");
    g.depth = r.has("depth") ? readLength(r, "depth") : g.width;
    if (g.depth > g.radius)
      r.fail("depth", "depth " + core::formatShort(g.depth) + " m exceeds the radius " +
                          core::formatShort(g.radius) + " m (the beam would cross its axis)");
  }
  return g;
}

/// The motion keys: `velocity`, and for a free sphere `mass` (gravity from
/// [gravity] when the case has one).
void readMotion(const core::TableReader& root, const core::TableReader& r, ContactSurface& s) {
  if (r.has("velocity"))
    s.velocity = readVector(r, "velocity", "[vx, vy, vz] (m/s)");
  if (!r.has("mass"))
    return;
  if (s.geometry.shape != SurfaceShape::Sphere)
    r.fail("mass", "only a sphere can be a free body (mass); give the others a velocity");
  s.mass = r.getDouble("mass");
  if (!(s.mass > 0))
    r.fail("mass", "mass must be > 0 (kg), got " + core::formatShort(s.mass));
  if (auto g = root.optionalTable("gravity")) {
    const auto gv = g->getDoubleArray("g");
    if (gv.size() == 3) // readGravity() names a wrong size
      s.gravity = Eigen::Vector3d(gv[0], gv[1], gv[2]);
  }
}

/// The contact keys: penalty, contact_damping, friction, slip_velocity,
/// penetration_tolerance.
void readContactKeys(const core::TableReader& r, const Mesh& mesh, ContactSurface& s) {
  s.penalty = r.getDouble("penalty");
  if (!(s.penalty > 0))
    r.fail("penalty", "penalty must be > 0 (N/m per node), got " + core::formatShort(s.penalty));
  s.damping = r.getDouble("contact_damping", 0.0);
  if (!(s.damping >= 0 && s.damping < 1))
    r.fail("contact_damping", "contact_damping is a fraction of critical damping in [0, 1), got " +
                                  core::formatShort(s.damping));
  s.friction = r.getDouble("friction", 0.0);
  if (!(s.friction >= 0))
    r.fail("friction", "friction coefficient must be >= 0, got " + core::formatShort(s.friction));
  if (r.has("slip_velocity") && s.friction == 0)
    r.fail("slip_velocity", "slip_velocity regularizes friction: give friction > 0");
  s.slip_velocity = r.has("slip_velocity") ? readLength(r, "slip_velocity") : kSlipVelocity;
  s.tolerance = r.has("penetration_tolerance") ? readLength(r, "penetration_tolerance")
                                               : defaultPenetrationTolerance(s.geometry, mesh);
}

} // namespace

void readRigidSurfaces(const core::TableReader& root, Model& model) {
  std::set<std::string> names;
  for (const auto& c : model.constraints)
    names.insert(c.name);
  for (const auto& sp : model.springs)
    names.insert(sp->name());
  for (const auto& r : root.tableArray("rigid_surface")) {
    ContactSurface s;
    s.name = r.getString("name", "surface" + std::to_string(model.contact.size()));
    if (const std::string why = core::nameProblem(s.name); !why.empty())
      r.fail("name", "rigid surface name " + why); // names CSV columns
    if (!names.insert(s.name).second)
      r.fail("name", "the name '" + s.name + "' is already a constraint, spring or rigid surface");
    s.geometry = readGeometry(r);
    readMotion(root, r, s);
    readContactKeys(r, model.mesh, s);
    s.nodes = selectNodes(model.mesh, readSelectorOrAll(r), r);
    model.contact.push_back(std::move(s));
  }
}

} // namespace lamina::membrane::case_io
