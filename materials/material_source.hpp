#pragma once
/// @file material_source.hpp
/// @brief Finding a material by name where users keep them: the library
/// first, then the catalog of base materials.

#include "materials/catalog.hpp"
#include "materials/law.hpp"
#include "materials/library.hpp"
#include "materials/reduced_order_law.hpp"

#include <filesystem>
#include <memory>
#include <string>

namespace lamina::materials {

/// The cell of the reduced-order entry @p m of @p library: its phases from
/// the entry, its arrays from its side file (relative to library.folder()).
/// Throws lamina::Error naming the entry and the file when the entry is not
/// reduced-order, the side file is missing, its fileChecksum differs from
/// the entry's side_checksum (changed after the library wrote it) or it is
/// malformed (readReducedOrderArrays).
ReducedOrderModel readReducedOrderEntry(const Library& library, const Material& m);

/// The library and the catalog, each loaded on first use. Contract: get()
/// returns the library entry of that name if there is one (the library
/// wins), else the catalog entry as a Material carrying the catalog's
/// nominal thickness (if any) as its thickness; otherwise it throws
/// lamina::Error with unknownMessage(): where it looked and how an entry is
/// made.
class MaterialSource {
public:
  /// @param library library file (Library::resolvePath is applied to it)
  /// @param catalog catalog file; empty: Catalog::defaultPath(). A catalog
  ///        file that does not exist is treated as an empty catalog.
  explicit MaterialSource(const std::string& library, const std::string& catalog = "");

  /// @return the material named @p name (see the class contract)
  Material get(const std::string& name);
  /// @return the constitutive law of @p name: a reduced-order library entry
  /// is a ReducedOrderLaw with @p options (readReducedOrderEntry), another
  /// library entry is linear elastic with its C (LawKind::Anisotropic), a
  /// catalog entry has its own law (GVBO included); unknown names as get()
  LawPtr law(const std::string& name, const ReducedOrderOptions& options = {});
  /// @return whether the library or the catalog has @p name
  bool contains(const std::string& name);
  /// @return the message for a @p name that neither holds: the library's
  /// path and entries, the catalog's path and entries, and @p make (the
  /// command that makes the entry, when the caller knows it) or else the
  /// generic hint: `homogenize CELL.toml --name NAME --library L` makes a
  /// cell's entry, `materials --library L list` lists the library
  std::string unknownMessage(const std::string& name, const std::string& make = "");
  /// @return the library (loaded now if not yet)
  const Library& library();

private:
  const Catalog* catalog();
  std::filesystem::path library_path_, catalog_path_;
  std::unique_ptr<Library> library_;
  std::unique_ptr<Catalog> catalog_;
  bool catalog_tried_ = false;
};

} // namespace lamina::materials
