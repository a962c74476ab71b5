#include "materials/catalog.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"

#include <cstdlib>

#ifndef LAMINA_CATALOG_PATH
#define LAMINA_CATALOG_PATH "materials/catalog.toml"
#endif

namespace lamina::materials {

namespace {
Stiffness readMatrix(const core::TableReader& t, const std::string& key) {
  const auto rows = t.getMatrix(key);
  if (rows.size() != 6)
    t.fail(key, "expected 6 rows of 6 numbers");
  Matrix6 c;
  for (int i = 0; i < 6; ++i) {
    if (rows[static_cast<std::size_t>(i)].size() != 6)
      t.fail(key, "expected 6 rows of 6 numbers");
    for (int j = 0; j < 6; ++j)
      c(i, j) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  return Stiffness(c);
}

// Stiffness of a transversely isotropic material with axis x from its
// engineering constants, by inverting the compliance (lamina order,
// engineering shear; G23 = E2 / (2 (1 + nu23)) in the isotropic plane).
Stiffness transverselyIsotropic(double E1, double E2, double G12, double nu12, double nu23) {
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

} // namespace

Material CatalogEntry::toMaterial() const {
  Material m;
  m.name = name;
  m.C = C;
  m.density = density;
  m.kind = "catalog";
  m.provenance.insert("source", source);
  m.provenance.insert("description", description);
  m.provenance.insert("law", law);
  return m;
}

std::filesystem::path Catalog::defaultPath() {
  if (const char* env = std::getenv("LAMINA_CATALOG"); env && *env)
    return env;
  return LAMINA_CATALOG_PATH;
}

Catalog::Catalog(const std::filesystem::path& path) : path_(path) {
  const toml::table doc = core::parseTomlFile(path);
  const core::TableReader root(doc, path.string());
  for (const std::string& name : root.keys()) {
    const core::TableReader t = root.table(name);
    CatalogEntry e;
    e.name = name;
    e.description = t.getString("description");
    e.source = t.getString("source");
    e.density = t.getDouble("density");
    if (!(e.density > 0))
      t.fail("density", "density must be positive (kg/m^3)");
    e.law = t.getString("law");
    if (t.has("nominal_thickness"))
      e.nominal_thickness = t.getDouble("nominal_thickness");
    try {
      if (e.law == "isotropic" || e.law == "gvbo") {
        const double E = t.getDouble("E"), nu = t.getDouble("nu");
        e.C = Stiffness::isotropic(E, nu);
        if (e.law == "gvbo")
          e.gvbo = readGvboParameters(t.table("gvbo"), E, nu);
      } else if (e.law == "transversely-isotropic") {
        e.C = transverselyIsotropic(t.getDouble("E1"), t.getDouble("E2"), t.getDouble("G12"),
                                    t.getDouble("nu12"), t.getDouble("nu23"));
      } else if (e.law == "anisotropic") {
        e.C = readMatrix(t, "C");
      } else {
        t.fail("law", "unknown law '" + e.law +
                          "' (isotropic, transversely-isotropic, anisotropic, gvbo)");
      }
      e.C.validate(name);
    } catch (const Error& err) {
      if (!err.context().file.empty())
        throw;
      throw Error(err.message(), {path.string(), 0, name});
    }
    entries_.emplace(name, std::move(e));
  }
  root.finish();
}

std::vector<std::string> Catalog::names() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : entries_)
    out.push_back(k);
  return out;
}

const CatalogEntry& Catalog::get(const std::string& name) const {
  auto it = entries_.find(name);
  if (it == entries_.end())
    throw Error("no such material in catalog " + path_.string() +
                    " (it holds: " + core::joinNames(names()) + ")",
                {"", 0, name});
  return it->second;
}

} // namespace lamina::materials
