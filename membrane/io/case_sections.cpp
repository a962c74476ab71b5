/// @file case_sections.cpp
/// @brief [[section]] of a case: a constitutive law by material name, inline
/// (`law` and its keys, or the shortcuts E and C), or plies.

#include "membrane/io/case_builders.hpp"

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "materials/catalog.hpp"
#include "materials/law_spec.hpp"
#include "materials/layup.hpp"
#include "materials/library.hpp"
#include "materials/material_source.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>

namespace lamina::membrane::case_io {

namespace {

/// The large-deflection keys of a [[section]].
constexpr std::array<const char*, 6> kFabricKeys = {
    "material_axis", "prestress", "tension_only", "wrinkling", "failure_strain", "failure_stress"};
/// The keys of a [[section]] with an inline law that are not its law's
/// (with kFabricKeys; the law's own keys are materials::readLawSpec's).
constexpr std::array<const char*, 5> kOwnKeys = {"region", "density", "thickness", "dispersion",
                                                 "micro_inertia"};

/// Runs @p f (a look-up in the material sources, a ply, a law's own check of
/// its parameters); an error without a file of its own (an unknown name, a
/// reduced-order entry's side file, GVBO's Et >= E0) is blamed on @p key of
/// @p r, while a broken library or catalog file keeps its file and line.
template <class F>
auto blamed(const core::TableReader& r, const std::string& key, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error& e) {
    if (!e.context().file.empty())
      throw;
    r.fail(key, e.message());
  }
}

/// @return "the section of region 'NAME'" (or of every region left) for messages
std::string sectionText(const core::TableReader& r) {
  return r.has("region") ? "the section of region '" + r.getString("region") + "'"
                         : "the section of every region without one of its own";
}

/// `material_from = "CELL.toml"` (relative to the case file) names the cell
/// file `homogenize` makes the section's material from; read when the
/// material is in neither the library nor the catalog.
/// @return the command that makes material @p name into the library of
/// @p source (the cell file must exist)
std::string makeCommand(const core::TableReader& r, const std::string& name,
                        materials::MaterialSource& source) {
  std::filesystem::path cell = r.getString("material_from");
  if (cell.is_relative())
    cell = std::filesystem::path(r.file()).parent_path() / cell;
  cell = cell.lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(cell, ec))
    r.fail("material_from", "the cell file " + cell.string() + " (that makes material '" + name +
                                "'; relative to the case file) does not exist");
  return "homogenize " + core::shellWord(cell.string()) + " --name " + core::shellWord(name) +
         " --library " + core::shellWord(source.library().path().string());
}

/// `material = "NAME"`: the law of the library or catalog entry
/// (MaterialSource::law: a reduced-order entry is its ReducedOrderLaw, a
/// catalog entry its own law), its density and dispersion. A name neither
/// holds is an error saying where it looked and how the entry is made
/// (with `material_from`, the very command).
/// @return the entry's thickness, if it has one (the section's default)
std::optional<double> readNamedMaterial(const core::TableReader& r,
                                        materials::MaterialSource& source, Section& s) {
  const std::string name = r.getString("material");
  if (r.has("material_from") && !blamed(r, "material", [&] { return source.contains(name); }))
    r.fail("material", source.unknownMessage(name, makeCommand(r, name, source)));
  (void)r.getString("material_from", ""); // read: only the message above uses it
  const materials::Material m = blamed(r, "material", [&] { return source.get(name); });
  s.law = blamed(r, "material", [&] { return source.law(name); });
  s.D = s.law->elasticStiffness(1.0).matrix(); // a linear law: the entry's C, bit for bit
  s.density = m.density;
  if (m.dispersion)
    s.dispersion = *m.dispersion;
  s.material = name + " (" + materials::toString(s.law->kind()) + ")";
  return m.thickness;
}

/// Refuses a key of @p r that is neither a section key nor read by the law
/// (`law = "isotropic"` with C, a gvbo table on an elastic law), naming the
/// key and the law @p law. @p read reads the law from a reader; it is run
/// again on a reader of its own, which records the keys the law takes.
template <class Read>
void checkLawKeys(const core::TableReader& r, const Read& read, const std::string& law) {
  const core::TableReader own(r.tomlTable(), r.file());
  for (const char* k : kOwnKeys)
    own.raw(k);
  for (const char* k : kFabricKeys)
    own.raw(k);
  read(own);
  try {
    own.finish();
  } catch (const Error& e) {
    const std::string& key = e.context().key;
    if (key.find('.') == std::string::npos) // a key of the section, not one inside a law's table
      r.fail(key, "not a key of law \"" + law + "\" (nor of a section)");
  }
}

/// An inline law: `law = "NAME"` and that law's keys (materials::readLawSpec,
/// as cell phases and catalog entries), or the shortcuts E (with nu: law
/// "isotropic") and C (law "anisotropic"); `density` is required.
void readInlineLaw(const core::TableReader& r, Section& s) {
  const auto read = [](const core::TableReader& t) {
    if (t.has("law"))
      return materials::readLawSpec(t);
    return materials::readLawConstants(t, t.has("E") ? materials::LawKind::Isotropic
                                                     : materials::LawKind::Anisotropic);
  };
  const materials::LawSpec spec = read(r);
  checkLawKeys(r, read, materials::toString(spec.kind));
  // the law checks the ranges of its parameters (GvboLaw: Et < E0, k1 > 0, ...)
  s.law = blamed(r, spec.kind == materials::LawKind::Gvbo ? "gvbo" : "law",
                 [&] { return spec.make(); });
  s.D = s.law->elasticStiffness(1.0).matrix(); // a linear law: spec.C, bit for bit
  s.density = r.getDouble("density");
  s.material = std::string("inline ") + materials::toString(spec.kind);
}

/// `plies`: a linear laminate of elastic plies (materials::makeLayup); a ply
/// of a nonlinear law (GVBO, a reduced-order cell) is refused.
/// @return the layup's thickness (the section's default)
std::optional<double> readLayup(const core::TableReader& r, materials::MaterialSource& source,
                                Section& s) {
  const auto texts = r.getStringArray("plies");
  std::vector<materials::Ply> plies;
  for (const auto& t : texts)
    plies.push_back(blamed(r, "plies", [&] { return materials::parsePly(t); }));
  const auto elasticPly = [&](const std::string& name) {
    const materials::Material m = blamed(r, "plies", [&] { return source.get(name); });
    // a reduced-order entry is refused by its kind, before its side file is read
    const bool reduced = m.kind == materials::kReducedOrderKind;
    const materials::LawPtr law =
        reduced ? nullptr : blamed(r, "plies", [&] { return source.law(name); });
    if (reduced || !law->isLinear())
      r.fail("plies",
             "ply material '" + name + "' has a nonlinear law (" +
                 materials::toString(reduced ? materials::LawKind::ReducedOrder : law->kind()) +
                 "): a layup is a linear laminate of elastic plies; give it as a "
                 "section's material instead");
    return m;
  };
  const materials::Material m =
      blamed(r, "plies", [&] { return materials::makeLayup("case-layup", plies, elasticPly); });
  s.law = std::make_shared<materials::LinearElasticLaw>(materials::LawKind::Anisotropic, m.C);
  s.D = m.C.matrix();
  s.density = m.density;
  if (m.dispersion)
    s.dispersion = *m.dispersion;
  s.material = "layup of " + std::to_string(plies.size()) + " plies (anisotropic)";
  return m.thickness;
}

/// A nonlinear law needs the large-deflection model and carries no
/// micro-inertia; the large-deflection model carries none either.
void checkLawFitsModel(const core::TableReader& r, ModelKind kind, const Section& s) {
  if (!s.isLinear()) {
    const std::string what = sectionText(r) + " has the nonlinear law " + s.material;
    if (kind == ModelKind::Linear)
      r.failHere(what + ", which the linear (paper's) model cannot carry: set model = "
                        "\"large_deflection\"");
    if (s.hasMicroInertia())
      r.failHere(what + " and micro-inertia (a dispersion), which a nonlinear law does not "
                        "carry: set micro_inertia = false");
  }
  if (kind == ModelKind::LargeDeflection && s.hasMicroInertia())
    r.failHere("the material has micro-inertia (a dispersion), which only the linear model "
               "carries: set micro_inertia = false for the large-deflection model");
}

/// Micro-inertia keys of a section: an inline `dispersion` (zeta^2 D, 6x6,
/// kg/m) for inline materials, and `micro_inertia = false` to drop the
/// material's (on by default).
void readMicroInertia(const core::TableReader& r, bool named, Section& s) {
  if (r.has("dispersion")) {
    if (named)
      r.fail("dispersion",
             "only with an inline material (law, E or C): a named material brings its "
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
/// tension_only and its wrinkling law, failure thresholds); an error under
/// the linear model.
void readFabricKeys(const core::TableReader& r, ModelKind kind, Section& s) {
  for (const char* key : kFabricKeys)
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
    if (!s.isLinear())
      r.fail("prestress", "needs an elastic law: " + s.material + " starts unstressed");
  }
  s.tension_only = r.getBool("tension_only", false);
  if (s.tension_only && s.law && s.law->kind() == materials::LawKind::Fabric)
    r.fail("tension_only",
           "the fabric law already carries no compression along its yarns, and wrinkling on top "
           "of it is not supported (a slack element's yarns have no stiffness to solve the "
           "wrinkles with): leave tension_only out");
  s.wrinkling = r.getChoice("wrinkling", kWrinklingLawNames, WrinklingLaw::Relaxed);
  if (r.has("wrinkling") && !s.tension_only)
    r.fail("wrinkling", "chooses the law of a tension-only section: it needs tension_only = true");
  if (s.wrinkling == WrinklingLaw::Projection && !s.isLinear())
    r.fail("wrinkling", "\"projection\" needs an elastic law: " + s.material +
                            " wrinkles by its stress-free wrinkling strain (\"relaxed\")");
  s.failure_strain = r.getDouble("failure_strain", s.failure_strain);
  s.failure_stress = r.getDouble("failure_stress", s.failure_stress);
  if (!(s.failure_strain > 0))
    r.fail("failure_strain", "must be > 0");
  if (!(s.failure_stress > 0))
    r.fail("failure_stress", "must be > 0");
}

/// Reads one [[section]]: its law by material name, inline, or plies.
Section readSection(const core::TableReader& r, materials::MaterialSource& source, ModelKind kind) {
  const bool by_name = r.has("material"), layup = r.has("plies");
  const int inline_law = r.has("law") ? 1 : int(r.has("E")) + int(r.has("C"));
  if (by_name + layup + inline_law != 1)
    r.failHere("give exactly one of material, law (with its keys and density), E (with nu and "
               "density), C (with density), plies");
  if (r.has("material_from") && !by_name)
    r.fail("material_from", "names the cell file that makes the section's `material`; it goes "
                            "with material = \"NAME\"");
  Section s;
  std::optional<double> default_thickness;
  if (by_name)
    default_thickness = readNamedMaterial(r, source, s);
  else if (layup)
    default_thickness = readLayup(r, source, s);
  else
    readInlineLaw(r, s);
  readMicroInertia(r, by_name || layup, s);
  checkLawFitsModel(r, kind, s);
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
