#pragma once
/// @file material_sources.hpp
/// @brief Where the materials a case names come from (the options of
/// `membrane run`): shared by case_file.hpp and the section builder of
/// case_builders.hpp.

#include <string>

namespace lamina::membrane {

/// Where materials come from.
struct MaterialSources {
  std::string library_path; ///< --library (empty: Library::resolvePath default)
  std::string catalog_path; ///< empty: Catalog::defaultPath()
};

} // namespace lamina::membrane
