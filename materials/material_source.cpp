#include "materials/material_source.hpp"

#include "core/error.hpp"
#include "core/format.hpp"

#include <filesystem>

namespace lamina::materials {

MaterialSource::MaterialSource(const std::string& library, const std::string& catalog)
    : library_path_(Library::resolvePath(library)),
      catalog_path_(catalog.empty() ? Catalog::defaultPath() : std::filesystem::path(catalog)) {}

const Library& MaterialSource::library() {
  if (!library_)
    library_ = std::make_unique<Library>(library_path_);
  return *library_;
}

const Catalog* MaterialSource::catalog() {
  if (!catalog_tried_) {
    catalog_tried_ = true;
    if (std::filesystem::exists(catalog_path_))
      catalog_ = std::make_unique<Catalog>(catalog_path_);
  }
  return catalog_.get();
}

ReducedOrderModel readReducedOrderEntry(const Library& library, const Material& m) {
  const ErrorContext ctx{"", 0, m.name};
  if (m.kind != kReducedOrderKind)
    throw Error("entry of kind \"" + m.kind + "\" is not a reduced-order cell", ctx);
  const std::filesystem::path file = library.folder() / m.side_file;
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw Error("the side file of this reduced-order entry, " + file.string() +
                    ", is missing (write the entry again with `homogenize --reduced-order`)",
                ctx);
  const std::string sum = fileChecksum(file, "side file of '" + m.name + "'");
  if (sum != m.side_checksum)
    throw Error("the side file " + file.string() + " has checksum " + sum + " but the library " +
                    "recorded " + m.side_checksum +
                    ": it changed after the library wrote it; refusing to use it",
                ctx);
  ReducedOrderModel model;
  model.phases = m.phases;
  try {
    readReducedOrderArrays(file, model);
  } catch (const Error& e) {
    throw Error(e.what(), ctx);
  }
  return model;
}

LawPtr MaterialSource::law(const std::string& name, const ReducedOrderOptions& options) {
  if (!library().contains(name)) {
    const Catalog* cat = catalog();
    if (cat && cat->contains(name))
      return cat->get(name).makeLaw();
  }
  const Material m = get(name);
  if (m.kind == kReducedOrderKind)
    return std::make_shared<ReducedOrderLaw>(name, readReducedOrderEntry(library(), m), options);
  return std::make_shared<LinearElasticLaw>(LawKind::Anisotropic, m.C);
}

Material MaterialSource::get(const std::string& name) {
  const Library& lib = library();
  if (lib.contains(name))
    return lib.get(name);
  const Catalog* cat = catalog();
  if (cat && cat->contains(name)) {
    const CatalogEntry& entry = cat->get(name);
    Material m = entry.toMaterial();
    if (!m.thickness)
      m.thickness = entry.nominal_thickness;
    return m;
  }
  throw Error(unknownMessage(name), {"", 0, name});
}

bool MaterialSource::contains(const std::string& name) {
  const Catalog* cat = catalog();
  return library().contains(name) || (cat && cat->contains(name));
}

std::string MaterialSource::unknownMessage(const std::string& name, const std::string& make) {
  const Library& lib = library();
  const Catalog* cat = catalog();
  const auto holds = [](const std::vector<std::string>& names) {
    return names.empty() ? std::string("no entries") : "it has " + core::joinNames(names);
  };
  const std::string library_path = core::shellWord(lib.path().string());
  std::string text =
      "unknown material '" + name + "': not in library " + lib.path().string() + " (" +
      (std::filesystem::exists(lib.path()) ? holds(lib.names()) : "no such file") + ")";
  text += cat ? " nor in catalog " + catalog_path_.string() + " (" + holds(cat->names()) + ")"
              : " (no catalog at " + catalog_path_.string() + ")";
  if (!make.empty())
    return text + "; make it with: " + make;
  return text + "; `homogenize CELL.toml --name " + core::shellWord(name) + " --library " +
         library_path + "` makes a cell's entry, `materials --library " + library_path +
         " list` lists the library";
}

} // namespace lamina::materials
