#include "membrane/io/case_file.hpp"

#include "core/error.hpp"
#include "core/names.hpp"
#include "core/toml_reader.hpp"
#include "membrane/io/case_builders.hpp"

#include <algorithm>

namespace lamina::membrane {

namespace {

/// Top-level `model`: "linear" (default) or "large_deflection".
ModelKind readModelKind(const core::TableReader& root) {
  return root.getChoice("model", kModelKindNames, ModelKind::Linear);
}

} // namespace

using namespace case_io;

toml::table loadCaseDocument(const std::filesystem::path& path,
                             const std::vector<std::string>& overrides) {
  if (!std::filesystem::exists(path))
    throw Error("case file not found", ErrorContext{path.string(), 0, ""});
  toml::table doc = core::parseTomlFile(path);
  for (const auto& o : overrides)
    core::applyOverride(doc, o);
  return doc;
}

Model buildModel(const toml::table& doc, const std::filesystem::path& path,
                 const MaterialSources& sources) {
  core::TableReader root(doc, path.string());
  Model model;
  model.name = root.getString("name", path.stem().string());
  // The name becomes <name>.h5 and <name>.xdmf in the output folder.
  if (const std::string why = core::nameProblem(model.name); !why.empty())
    root.fail("name", "case name '" + model.name + "' " + why +
                          (root.has("name") ? "" : " (it is the file's stem: set name = ...)"));
  (void)root.getString("description", "");
  model.compare_without_drag = root.getBool("compare_without_drag", false);
  model.kind = readModelKind(root);
  model.mesh = readMesh(root.table("mesh"), path);
  if (model.kind == ModelKind::Linear && !model.mesh.flat())
    root.table("mesh").fail("file", "mesh " + model.mesh.source +
                                        " is not flat (z != 0): the linear model needs a mesh "
                                        "in the z = 0 plane; use model = \"large_deflection\"");
  readSections(root, sources, model);
  readTimeAndOutput(root, model);
  std::vector<int> owner = readConstraints(root, model);
  readLoads(root, model);
  readBlasts(root, model, path);
  readDrags(root, model);
  if (model.compare_without_drag &&
      std::none_of(model.surface_loads.begin(), model.surface_loads.end(),
                   [](const auto& l) { return l->kind() == WorkKind::Drag; }))
    root.fail("compare_without_drag", "needs at least one [[drag]] table");
  readSprings(root, model);
  readRigidSets(root, model, owner);
  readRigidSurfaces(root, model);
  checkIntegrator(root, model);
  readInitial(root, model);
  readProbes(root, model);
  root.finish();
  return model;
}

Model readCase(const std::filesystem::path& path, const std::vector<std::string>& overrides,
               const MaterialSources& sources) {
  return buildModel(loadCaseDocument(path, overrides), path, sources);
}

} // namespace lamina::membrane
