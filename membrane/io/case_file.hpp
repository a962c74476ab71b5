#pragma once
/// @file case_file.hpp
/// @brief Reading a membrane case file (TOML, docs/membrane.md) into a Model.
///
/// Contract: reading is strict (core::TableReader): an unknown key, a wrong
/// type, a bad value (dt <= 0, negative thickness), a missing mesh file, a
/// mesh without triangles or an unknown material is a lamina::Error naming
/// the file, line and key. Materials named in the case are looked up in the
/// materials library first, then in the catalog (the library wins).

#include "membrane/io/material_sources.hpp"
#include "membrane/system/model.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <string>
#include <vector>

namespace lamina::membrane {


/// Parses @p path and applies the `--set key=value` @p overrides.
toml::table loadCaseDocument(const std::filesystem::path& path,
                             const std::vector<std::string>& overrides);

/// Builds the model of document @p doc read from @p path (relative mesh
/// paths are resolved against the case file's folder).
Model buildModel(const toml::table& doc, const std::filesystem::path& path,
                 const MaterialSources& sources);

/// Convenience: loadCaseDocument + buildModel.
Model readCase(const std::filesystem::path& path, const std::vector<std::string>& overrides,
               const MaterialSources& sources);

} // namespace lamina::membrane
