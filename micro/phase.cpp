#include "micro/phase.hpp"

#include "core/error.hpp"
#include "core/toml_reader.hpp"
#include "materials/law_spec.hpp"
#include "materials/symmetry.hpp"

#include <cmath>

namespace lamina::micro {

materials::Stiffness Phase::stiffnessAt(double J) const {
  if (!gvbo)
    return C;
  // eqs. (13)-(16) of the polyurea chapter: instantaneous isotropic moduli at J.
  const materials::GvboModuli m = materials::gvboModuli(*gvbo, J);
  return materials::Stiffness::fromLame(m.lambda, m.G);
}

bool Phase::isotropic() const {
  return law == materials::LawKind::Isotropic || law == materials::LawKind::Gvbo ||
         law == materials::LawKind::Void ||
         materials::classify(C, 1e-12).cls == materials::SymmetryClass::Isotropic;
}

Phase readPhase(const core::TableReader& t, const CatalogProvider& catalog) {
  Phase ph;
  ph.name = t.getString("name");
  if (ph.name.empty())
    t.fail("name", "phase name must not be empty");
  if (t.has("catalog")) {
    const std::string cname = t.getString("catalog");
    const materials::Catalog& cat = catalog();
    if (!cat.contains(cname))
      t.fail("catalog", "no catalog entry '" + cname + "' in " + cat.path().string());
    const materials::CatalogEntry& e = cat.get(cname);
    ph.law = e.law;
    ph.source = "catalog:" + cname;
    ph.C = e.C;
    ph.density = e.density;
    ph.gvbo = e.gvbo;
    if (t.has("law") && materials::kLawKindNames.parse(t.getString("law")) != ph.law)
      t.fail("law", "catalog entry '" + cname + "' has law '" + materials::toString(ph.law) + "'");
  } else {
    ph.source = "inline";
    const materials::LawSpec law = materials::readLawSpec(t, materials::VoidLaw::Allowed);
    ph.law = law.kind;
    ph.C = law.C;
    ph.gvbo = law.gvbo;
  }
  if (ph.law == materials::LawKind::Fabric) // a membrane law: no thickness response of its own
    t.fail(t.has("catalog") ? "catalog" : "law",
           "the fabric law is a membrane law (yarns in the plane, no compression): a cell phase "
           "needs a 3D solid law");
  ph.model = ph.lawSpec().make();
  if (ph.isVoid()) { // a pore: no mass
    if (t.has("density"))
      t.fail("density", "a void phase (a pore) has zero density: leave density out");
  } else {
    if (t.has("density") || ph.source == "inline")
      ph.density = t.getDouble("density");
    if (!(ph.density > 0) || !std::isfinite(ph.density))
      t.fail("density", "density must be positive (kg/m^3)");
  }
  if (t.has("J")) {
    if (!ph.gvbo)
      t.fail("J", "a state J applies to gvbo phases only");
    const toml::node* n = t.tomlTable().get("J");
    if (n->is_array())
      ph.J = t.getDoubleArray("J");
    else
      ph.J = {t.getDouble("J")};
    if (ph.J.empty())
      t.fail("J", "must not be empty");
    for (double J : ph.J)
      if (!(J > 0) || !std::isfinite(J))
        t.fail("J", "volume ratio J must be positive");
  }
  return ph;
}

} // namespace lamina::micro
