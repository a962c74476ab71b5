/// @file case_sections.cpp
/// @brief [[section]] of a case: materials by name, inline, or plies.

#include "membrane/io/case_builders.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "materials/catalog.hpp"
#include "materials/layup.hpp"
#include "materials/library.hpp"
#include "materials/material_source.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

namespace lamina::membrane::case_io {

namespace {

/// Lazily opened material sources (a case with inline materials needs neither).
/// Looks a material up for the case (library, then catalog) and blames a
/// miss on the case file's key.
materials::Material lookupMaterial(materials::MaterialSource& source, const std::string& name,
                                   const core::TableReader& r, const std::string& key) {
  try {
    materials::Material m = source.get(name);
    if (m.kind == materials::kReducedOrderKind)
      r.fail(key, "'" + name + "' is a reduced-order cell, a nonlinear law: membrane sections "
                  "take elastic materials (its C alone would drop the law)");
    return m;
  } catch (const Error& e) {
    if (!e.context().file.empty())
      throw; // a broken library or catalog file: its own file and line
    r.fail(key, e.message());
  }
}

/// Micro-inertia keys of a section: an inline `dispersion` (zeta^2 D, 6x6,
/// kg/m) for inline materials, and `micro_inertia = false` to drop the
/// material's (on by default).
void readMicroInertia(const core::TableReader& r, bool named, Section& s) {
  if (r.has("dispersion")) {
    if (named)
      r.fail("dispersion", "only with an inline material (E or C): a named material brings its "
                           "own dispersion from the library");
    const auto d = r.getMatrix("dispersion");
    bool ok = d.size() == 6;
    for (const auto& row : d)
      ok = ok && row.size() == 6;
    if (!ok)
      r.fail("dispersion", "expected 6 rows of 6 (zeta^2 D, kg/m, lamina order)");
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        s.dispersion(i, j) = d[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    try {
      materials::validateDispersion(s.dispersion, "section");
    } catch (const Error& e) {
      r.fail("dispersion", e.message());
    }
  }
  if (!r.getBool("micro_inertia", true))
    s.dispersion.setZero();
}

/// The large-deflection keys of a [[section]] (material axis, pre-stress,
/// tension_only, failure thresholds); an error under the linear model.
void readFabricKeys(const core::TableReader& r, ModelKind kind, Section& s) {
  for (const char* key :
       {"material_axis", "prestress", "tension_only", "failure_strain", "failure_stress"})
    if (kind == ModelKind::Linear && r.has(key))
      r.fail(key, "needs model = \"large_deflection\"");
  if (kind == ModelKind::Linear)
    return;
  if (r.has("material_axis")) {
    const auto v = r.getDoubleArray("material_axis");
    if (v.size() != 3 || !(Eigen::Vector3d(v[0], v[1], v[2]).norm() > 0))
      r.fail("material_axis", "expected a non-zero [ax, ay, az]");
    s.axis = Eigen::Vector3d(v[0], v[1], v[2]).normalized();
  }
  if (r.has("prestress")) {
    const toml::node* node = r.raw("prestress");
    if (node->is_array()) {
      const auto v = r.getDoubleArray("prestress");
      if (v.size() != 3)
        r.fail("prestress", "expected a tension T (N/m) or [T11, T22, T12] (N/m)");
      s.prestress = {v[0], v[1], v[2]};
    } else {
      const double T = r.getDouble("prestress");
      s.prestress = {T, T, 0.0};
    }
    if (!s.prestress.allFinite())
      r.fail("prestress", "must be finite");
  }
  s.tension_only = r.getBool("tension_only", false);
  s.failure_strain = r.getDouble("failure_strain", s.failure_strain);
  s.failure_stress = r.getDouble("failure_stress", s.failure_stress);
  if (!(s.failure_strain > 0))
    r.fail("failure_strain", "must be > 0");
  if (!(s.failure_stress > 0))
    r.fail("failure_stress", "must be > 0");
}

/// Reads one [[section]]: material by name, inline isotropic/anisotropic, or plies.
Section readSection(const core::TableReader& r, materials::MaterialSource& res, ModelKind kind) {
  Section s;
  std::optional<double> default_thickness;
  const bool by_name = r.has("material"), iso = r.has("E"), aniso = r.has("C"),
             layup = r.has("plies");
  if (by_name + iso + aniso + layup != 1)
    r.failHere("give exactly one of material, E (with nu, density), C (with density), plies");
  if (by_name) {
    s.material = r.getString("material");
    const auto m = lookupMaterial(res, s.material, r, "material");
    s.D = m.C.matrix();
    s.density = m.density;
    if (m.dispersion)
      s.dispersion = *m.dispersion;
    default_thickness = m.thickness;
  } else if (iso) {
    const double E = r.getDouble("E"), nu = r.getDouble("nu");
    if (!(E > 0))
      r.fail("E", "must be > 0");
    if (!(nu > -1 && nu < 0.5))
      r.fail("nu", "must be in (-1, 0.5)");
    s.D = materials::Stiffness::isotropic(E, nu).matrix();
    s.density = r.getDouble("density");
    s.material = "isotropic E=" + std::to_string(E) + " nu=" + std::to_string(nu);
  } else if (aniso) {
    s.D = materials::readMatrix6(r, "C");
    s.density = r.getDouble("density");
    s.material = "inline C";
  } else {
    const auto texts = r.getStringArray("plies");
    std::vector<materials::Ply> plies;
    for (const auto& t : texts) {
      try {
        plies.push_back(materials::parsePly(t));
      } catch (const Error& e) {
        r.fail("plies", e.message());
      }
    }
    materials::Material m;
    try {
      m = materials::makeLayup("case-layup", plies, [&](const std::string& n) {
        return lookupMaterial(res, n, r, "plies");
      });
    } catch (const Error& e) {
      if (!e.context().file.empty())
        throw;
      r.fail("plies", e.message());
    }
    s.D = m.C.matrix();
    s.density = m.density;
    if (m.dispersion)
      s.dispersion = *m.dispersion;
    default_thickness = m.thickness;
    s.material = "layup of " + std::to_string(plies.size()) + " plies";
  }
  readMicroInertia(r, by_name || layup, s);
  if (kind == ModelKind::LargeDeflection && s.hasMicroInertia())
    r.failHere("the material has micro-inertia (a dispersion), which only the linear model "
               "carries: set micro_inertia = false for the large-deflection model");
  if (r.has("thickness") || !default_thickness) {
    s.thickness = r.getDouble("thickness");
    if (!(s.thickness > 0))
      r.fail("thickness", "thickness must be > 0");
  } else {
    s.thickness = *default_thickness;
  }
  if (!(s.density > 0) || !std::isfinite(s.density))
    r.failHere("density must be finite and > 0");
  try {
    materials::Stiffness(s.D).validate(s.material);
  } catch (const Error& e) {
    r.failHere(e.message());
  }
  readFabricKeys(r, kind, s);
  return s;
}

} // namespace

/// [[section]]: one per region; a section without `region` covers every region left.
void readSections(const core::TableReader& root, const MaterialSources& sources, Model& model) {
  const Mesh& mesh = model.mesh;
  materials::MaterialSource resolver(sources.library_path, sources.catalog_path);
  model.sections.assign(mesh.regions.size(), Section{});
  std::vector<bool> assigned(mesh.regions.size(), false);
  const auto sections = root.tableArray("section");
  if (sections.empty())
    root.fail("section", "at least one [[section]] is required");
  for (const auto& sr : sections) {
    const Section s = readSection(sr, resolver, model.kind);
    if (sr.has("region")) {
      const int reg = regionIndex(mesh, sr.getString("region"), sr, "region");
      if (assigned[reg])
        sr.fail("region", "region '" + mesh.regions[reg] + "' assigned twice");
      model.sections[reg] = s;
      model.sections[reg].name = mesh.regions[reg];
      assigned[reg] = true;
    } else {
      for (size_t g = 0; g < assigned.size(); ++g)
        if (!assigned[g]) {
          model.sections[g] = s;
          model.sections[g].name = mesh.regions[g];
          assigned[g] = true;
        }
    }
  }
  for (size_t g = 0; g < assigned.size(); ++g)
    if (!assigned[g])
      root.fail("section", "mesh region '" + mesh.regions[g] + "' has no section");
}

} // namespace lamina::membrane::case_io
