#include "materials/catalog.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "materials/law_spec.hpp"

#include <cstdlib>

#ifndef LAMINA_CATALOG_PATH
#define LAMINA_CATALOG_PATH "materials/catalog.toml"
#endif

namespace lamina::materials {

LawPtr CatalogEntry::makeLaw() const {
  return LawSpec{law, C, gvbo, fabric}.make();
}

Material CatalogEntry::toMaterial() const {
  Material m;
  m.name = name;
  m.C = C;
  m.density = density;
  m.kind = "catalog";
  m.provenance.insert("source", source);
  m.provenance.insert("description", description);
  m.provenance.insert("law", toString(law));
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
    if (const std::string why = core::nameProblem(name); !why.empty())
      t.failHere("material name " + why);
    e.description = t.getString("description");
    e.source = t.getString("source");
    e.density = t.getDouble("density");
    if (!(e.density > 0))
      t.fail("density", "density must be positive (kg/m^3)");
    if (t.has("nominal_thickness"))
      e.nominal_thickness = t.getDouble("nominal_thickness");
    LawSpec law = readLawSpec(t);
    e.law = law.kind;
    e.C = law.C;
    e.gvbo = law.gvbo;
    e.fabric = law.fabric;
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
