#pragma once
/// @file catalog.hpp
/// @brief The catalog of base materials (materials/catalog.toml).
///
/// Each catalog entry is `[NAME]` with `description`, `source`, `density`
/// (kg/m^3, required) and a law: `law = "isotropic"` with `E`, `nu`;
/// `law = "transversely-isotropic"` with `E1, E2, G12, nu12, nu23` (axis x);
/// `law = "anisotropic"` with `C` (6x6, Pa, lamina order); or `law = "gvbo"`
/// with `E`, `nu` (= E0, nu0) and a `[NAME.gvbo]` table of the other
/// parameters in SI units; or `law = "fabric"` with E_warp (or warp_curve),
/// E_fill (or fill_curve), G12 (fabric_law.hpp; a curve file is relative to
/// the catalog). Optional `nominal_thickness` (m).

#include "materials/fabric_law.hpp"
#include "materials/gvbo.hpp"
#include "materials/law.hpp"
#include "materials/material.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lamina::materials {

/// One base material of the catalog.
struct CatalogEntry {
  std::string name;                        ///< key in the catalog
  std::string description;                 ///< one line for humans
  std::string source;                      ///< where the numbers come from
  LawKind law = LawKind::Isotropic;        ///< which law (law_spec.hpp)
  double density = 0;                      ///< kg/m^3
  Stiffness C;                             ///< elastic stiffness (for gvbo: at J = 1, i.e. E0, nu0)
  std::optional<GvboParameters> gvbo;      ///< GVBO parameters for law = "gvbo"
  std::optional<FabricParameters> fabric;  ///< yarn curves and G12 for law = "fabric"
  std::optional<double> nominal_thickness; ///< m, where the source gives one
  /// @return the law object of this entry (LawSpec::make)
  LawPtr makeLaw() const;
  /// @return this entry as a library Material of kind "catalog"
  Material toMaterial() const;
};

/// The catalog file, validated strictly on load.
class Catalog {
public:
  /// Default catalog path: $LAMINA_CATALOG, else the source tree's catalog.
  static std::filesystem::path defaultPath();
  /// Loads and validates @p path.
  explicit Catalog(const std::filesystem::path& path = defaultPath());
  /// @return entry names, sorted
  std::vector<std::string> names() const;
  /// @return whether @p name is in the catalog
  bool contains(const std::string& name) const { return entries_.count(name) > 0; }
  /// @return entry @p name; error naming the catalog file and its entries if absent
  const CatalogEntry& get(const std::string& name) const;
  /// @return the catalog file path
  const std::filesystem::path& path() const { return path_; }

private:
  std::filesystem::path path_;
  std::map<std::string, CatalogEntry> entries_;
};

} // namespace lamina::materials
