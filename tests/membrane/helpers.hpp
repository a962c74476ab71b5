#pragma once
// Shared helpers of the membrane tests: build a Model from TOML text with
// inline or catalog materials (never the user's library).
#include "core/toml_reader.hpp"
#include "membrane/case_file.hpp"
#include "core/error.hpp"
#include "membrane/simulation.hpp"

#include <filesystem>
#include <string>

namespace lamina::membrane::test {

/// Material sources for tests: an empty library in the temp folder and the
/// source tree's catalog.
inline MaterialSources testSources() {
  const auto lib = std::filesystem::temp_directory_path() / "lamina-membrane-test-no-library.toml";
  std::filesystem::remove(lib);
  return {lib.string(), std::string(LAMINA_SOURCE_DIR) + "/materials/catalog.toml"};
}

/// Builds a model from case text (name "test.toml" in errors).
inline Model modelFromText(const std::string& text, const std::string& name = "test.toml") {
  const toml::table doc = core::parseTomlString(text, name);
  return buildModel(doc, std::filesystem::path(LAMINA_SOURCE_DIR) / "cases/membrane" / name,
                    testSources());
}

/// Path of a file in the source tree.
inline std::filesystem::path sourcePath(const std::string& rel) {
  return std::filesystem::path(LAMINA_SOURCE_DIR) / rel;
}

} // namespace lamina::membrane::test
