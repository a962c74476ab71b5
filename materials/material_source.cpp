#include "materials/material_source.hpp"

#include "core/error.hpp"
#include "core/format.hpp"

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

LawPtr MaterialSource::law(const std::string& name) {
  if (!library().contains(name)) {
    const Catalog* cat = catalog();
    if (cat && cat->contains(name))
      return cat->get(name).makeLaw();
  }
  return std::make_shared<LinearElasticLaw>(LawKind::Anisotropic, get(name).C);
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
  throw Error("unknown material '" + name + "': library " + lib.path().string() + " has [" +
                  core::joinNames(lib.names()) + "]" +
                  (cat ? "; catalog has [" + core::joinNames(cat->names()) + "]" : ""),
              {"", 0, name});
}

} // namespace lamina::materials
