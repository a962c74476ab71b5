#include "micro/phase.hpp"

#include "core/error.hpp"
#include "core/toml_reader.hpp"

#include <cmath>

namespace lamina::micro {

materials::Stiffness Phase::stiffnessAt(double J) const {
  if (!gvbo)
    return C;
  // eqs. (13)-(16) of the polyurea chapter: instantaneous isotropic moduli at J.
  const materials::GvboModuli m = materials::gvboModuli(*gvbo, J);
  return materials::Stiffness::fromLame(m.lambda, m.G);
}

namespace {

materials::Stiffness isotropicChecked(const core::TableReader& t, double E, double nu) {
  if (!(E > 0) || !std::isfinite(E))
    t.fail("E", "Young's modulus must be positive");
  if (!(nu > -1.0 && nu < 0.5))
    t.fail("nu", "Poisson ratio must lie in (-1, 0.5)");
  return materials::Stiffness::isotropic(E, nu);
}

} // namespace

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
    if (t.has("law") && t.getString("law") != ph.law)
      t.fail("law", "catalog entry '" + cname + "' has law '" + ph.law + "'");
  } else {
    ph.source = "inline";
    ph.law = t.getString("law");
    if (ph.law == "isotropic") {
      ph.C = isotropicChecked(t, t.getDouble("E"), t.getDouble("nu"));
    } else if (ph.law == "anisotropic") {
      const auto m = t.getMatrix("C");
      if (m.size() != 6)
        t.fail("C", "must have 6 rows of 6 (lamina order, Pa)");
      materials::Matrix6 c;
      for (int i = 0; i < 6; ++i) {
        if (m[static_cast<std::size_t>(i)].size() != 6)
          t.fail("C", "must have 6 rows of 6 (lamina order, Pa)");
        for (int j = 0; j < 6; ++j)
          c(i, j) = m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      }
      ph.C = materials::Stiffness(c);
    } else if (ph.law == "gvbo") {
      const double E = t.getDouble("E"), nu = t.getDouble("nu");
      ph.C = isotropicChecked(t, E, nu);
      ph.gvbo = materials::readGvboParameters(t.table("gvbo"), E, nu);
    } else {
      t.fail("law", "unknown law '" + ph.law + "' (isotropic, anisotropic, gvbo)");
    }
  }
  if (t.has("density") || ph.source == "inline")
    ph.density = t.getDouble("density");
  if (!(ph.density > 0) || !std::isfinite(ph.density))
    t.fail("density", "density must be positive (kg/m^3)");
  try {
    ph.C.validate("phase '" + ph.name + "'");
  } catch (const Error& e) {
    t.fail(t.has("C") ? "C" : "name", e.message());
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
