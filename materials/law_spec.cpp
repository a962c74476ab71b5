#include "materials/law_spec.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"
#include "materials/gvbo_law.hpp"

#include <cmath>
#include <ostream>

namespace lamina::materials {

Stiffness transverselyIsotropic(double E1, double E2, double G12, double nu12, double nu23) {
  // invert the compliance (lamina order, engineering shear)
  Matrix6 s = Matrix6::Zero();
  s(0, 0) = 1 / E1;
  s(1, 1) = s(2, 2) = 1 / E2;
  s(0, 1) = s(1, 0) = s(0, 2) = s(2, 0) = -nu12 / E1;
  s(1, 2) = s(2, 1) = -nu23 / E2;
  s(3, 3) = 1 / G12;             // xy
  s(4, 4) = 2 * (1 + nu23) / E2; // yz, the isotropic plane
  s(5, 5) = 1 / G12;             // xz
  return Stiffness(s.inverse()).symmetrized();
}

namespace {

constexpr const char* kReducedOrderIsAnEntry =
    "'reduced-order' is not a law with keys: a reduced-order cell is a library entry made by "
    "`homogenize --reduced-order`, referred to by its name (materials drive NAME)";

constexpr const char* kVoidIsAPore =
    "'void' is a pore (zero stiffness): only a cell's [[phases]] may have one";

/// A void law has no elastic constants: the first one @p t gives is an error.
void checkNoConstants(const core::TableReader& t) {
  for (const char* key : {"E", "nu", "C", "E1", "E2", "G12", "nu12", "nu23", "gvbo", "E_warp",
                          "E_fill", "warp_curve", "fill_curve"})
    if (t.has(key))
      t.fail(key, "a void phase (a pore) has zero stiffness: no elastic constants");
}

double positive(const core::TableReader& t, const char* key) {
  const double v = t.getDouble(key);
  if (!(v > 0) || !std::isfinite(v))
    t.fail(key, "must be positive (Pa)");
  return v;
}

double poisson(const core::TableReader& t, const char* key) {
  const double nu = t.getDouble(key);
  if (!(nu > -1.0 && nu < 0.5))
    t.fail(key, "Poisson ratio must lie in (-1, 0.5)");
  return nu;
}

} // namespace

LawSpec readLawConstants(const core::TableReader& t, LawKind kind) {
  LawSpec s;
  s.kind = kind;
  switch (kind) {
  case LawKind::Isotropic:
  case LawKind::Gvbo: {
    const double E = positive(t, "E"), nu = poisson(t, "nu");
    s.C = Stiffness::isotropic(E, nu);
    if (kind == LawKind::Gvbo)
      s.gvbo = readGvboParameters(t.table("gvbo"), E, nu);
    break;
  }
  case LawKind::TransverselyIsotropic:
    s.C = transverselyIsotropic(positive(t, "E1"), positive(t, "E2"), positive(t, "G12"),
                                t.getDouble("nu12"), t.getDouble("nu23"));
    break;
  case LawKind::Anisotropic:
    s.C = Stiffness(readMatrix6(t, "C"));
    break;
  case LawKind::Fabric:
    s.fabric = readFabricParameters(t);
    s.C = FabricLaw(*s.fabric).elasticStiffness(1.0);
    return s; // diagonal and positive by construction
  case LawKind::ReducedOrder:
    t.fail("law", kReducedOrderIsAnEntry);
  case LawKind::Void:
    checkNoConstants(t);
    return s; // C = 0: nothing to validate
  }
  try {
    s.C.validate("law");
  } catch (const Error& e) {
    t.fail(t.has("C") ? "C" : "law", e.message());
  }
  return s;
}

LawPtr LawSpec::make() const {
  if (kind == LawKind::Gvbo) {
    LAMINA_CHECK(gvbo.has_value(), "gvbo law without its parameters");
    return std::make_shared<GvboLaw>(*gvbo);
  }
  if (kind == LawKind::Fabric) {
    LAMINA_CHECK(fabric.has_value(), "fabric law without its parameters");
    return std::make_shared<FabricLaw>(*fabric);
  }
  LAMINA_CHECK(kind != LawKind::ReducedOrder, kReducedOrderIsAnEntry);
  return std::make_shared<LinearElasticLaw>(kind, C); // void: C = 0
}

void writeLawSpec(std::ostream& os, const LawSpec& law) {
  LAMINA_CHECK(law.kind != LawKind::ReducedOrder, kReducedOrderIsAnEntry);
  LAMINA_CHECK(law.kind != LawKind::Void, kVoidIsAPore);
  LAMINA_CHECK(law.kind != LawKind::Fabric, "a fabric law is not written as a law spec");
  if (law.kind != LawKind::Gvbo) {
    os << "law = \"" << toString(LawKind::Anisotropic) << "\"\n";
    writeMatrix6(os, "C", law.C.matrix());
    return;
  }
  LAMINA_CHECK(law.gvbo.has_value(), "gvbo law without its parameters");
  const GvboParameters& g = *law.gvbo;
  os << "law = \"" << toString(LawKind::Gvbo) << "\"\nE = " << core::formatExact(g.E0)
     << "\nnu = " << core::formatExact(g.nu0) << "\ngvbo = { ";
  const char* sep = "";
  for (const auto& [key, member] : gvboTableKeys()) {
    os << sep << key << " = " << core::formatExact(g.*member);
    sep = ", ";
  }
  os << " }\n";
}

LawSpec readLawSpec(const core::TableReader& t, VoidLaw void_law) {
  const std::string name = t.getString("law");
  const std::optional<LawKind> kind = kLawKindNames.parse(name);
  const bool pores = void_law == VoidLaw::Allowed;
  if (!kind)
    t.fail("law", "unknown law '" + name + "' (expected " + lawKindNames() +
                      (pores ? ", or 'void' for a pore)" : ")"));
  if (*kind == LawKind::ReducedOrder)
    t.fail("law", kReducedOrderIsAnEntry);
  if (*kind == LawKind::Void && !pores)
    t.fail("law", kVoidIsAPore);
  if (pores && *kind != LawKind::Void && t.has("E") && t.getDouble("E") == 0)
    t.fail("E", "must be positive (Pa); a pore is law = \"void\" (no E, nu or density)");
  return readLawConstants(t, *kind);
}

} // namespace lamina::materials
