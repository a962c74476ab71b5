#include "materials/layup.hpp"

#include "core/error.hpp"
#include "core/format.hpp"

#include <cmath>
#include <cstdlib>

namespace lamina::materials {

namespace {
double parseNumber(const std::string& s, const std::string& what, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
    throw Error("ply " + what + " '" + s +
                    "' is not a number (expected MATERIAL:ANGLE_DEG:THICKNESS_M)",
                {"--ply", 0, text});
  return v;
}
} // namespace

Ply parsePly(const std::string& text) {
  const auto b = text.rfind(':');
  const auto a = b == std::string::npos || b == 0 ? std::string::npos : text.rfind(':', b - 1);
  if (a == std::string::npos || a == 0)
    throw Error("ply must read MATERIAL:ANGLE_DEG:THICKNESS_M", {"--ply", 0, text});
  Ply p;
  p.material = text.substr(0, a);
  p.angle_deg = parseNumber(text.substr(a + 1, b - a - 1), "angle", text);
  p.thickness = parseNumber(text.substr(b + 1), "thickness", text);
  if (!(p.thickness > 0))
    throw Error("ply thickness must be positive (m)", {"--ply", 0, text});
  return p;
}

Material makeLayup(const std::string& name, const std::vector<Ply>& plies,
                   const MaterialLookup& lookup) {
  if (plies.empty())
    throw Error("a layup needs at least one ply", {"", 0, name});
  double h = 0;
  for (const Ply& p : plies) {
    if (!(p.thickness > 0) || !std::isfinite(p.thickness))
      throw Error("ply thickness must be positive (m), got " + core::formatShort(p.thickness),
                  {"", 0, name + ": ply " + p.material});
    if (!(std::abs(p.angle_deg) <= kMaxPlyAngleDeg))
      throw Error("ply angle must be within -" + core::formatShort(kMaxPlyAngleDeg) + " to " +
                      core::formatShort(kMaxPlyAngleDeg) + " degrees, got " +
                      core::formatShort(p.angle_deg),
                  {"", 0, name + ": ply " + p.material});
    h += p.thickness;
  }
  Matrix6 sum = Matrix6::Zero(), dispersion = Matrix6::Zero();
  bool any_dispersion = false;
  double mass = 0;
  toml::array plyText;
  for (const Ply& p : plies) {
    const Material m = lookup(p.material);
    if (m.kind == kReducedOrderKind)
      throw Error("'" + p.material + "' is a reduced-order cell, a nonlinear law: a layup adds "
                  "elastic stiffnesses (its C alone would drop the law)",
                  {"", 0, name + ": ply " + p.material});
    // D = sum h_k R_k D_k R_k^T / h (DESIGN.md, "Layered membranes"): the same
    // strain acts through the thickness, so stiffnesses add by thickness.
    // Weights w_k = h_k / h are formed first so that one ply (w = 1) or two equal
    // plies of any thickness (w = 1/2) average without rounding.
    const double w = p.thickness / h;
    const Eigen::Matrix3d R = axisRotationDegrees(2, p.angle_deg);
    sum += w * m.C.rotated(R).matrix();
    // micro-inertia acts on the same strain rate: its energy adds by thickness
    // like the stiffness (a ply without dispersion contributes zero)
    if (m.dispersion) {
      dispersion += w * Stiffness(*m.dispersion).rotated(R).matrix();
      any_dispersion = true;
    }
    mass += w * m.density;
    plyText.push_back(p.material + ":" + core::formatShort(p.angle_deg, 17) + ":" +
                      core::formatShort(p.thickness, 17));
  }
  Material out;
  out.name = name;
  out.kind = "layup";
  out.C = Stiffness(sum).symmetrized();
  out.density = mass;
  out.thickness = h;
  if (any_dispersion)
    out.dispersion = 0.5 * (dispersion + dispersion.transpose());
  out.plies = plies;
  out.provenance.insert("method", "exact thickness average D = sum h_k R_k D_k R_k^T / h");
  if (any_dispersion)
    out.provenance.insert("dispersion_method",
                          "thickness average of the plies' zeta^2 D, rotated like C");
  out.provenance.insert("plies", plyText);
  validate(out);
  return out;
}

} // namespace lamina::materials
