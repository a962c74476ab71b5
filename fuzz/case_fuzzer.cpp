/// @file case_fuzzer.cpp
/// @brief libFuzzer target: membrane case files, parsed and built into a
/// Model (mesh, sections, constraints, loads, probes). Structured meshes are
/// capped at 64 x 64 cells so that one input runs in milliseconds (sizes
/// beyond are the malformed tests' business); gmsh meshes are left to the
/// .msh target (a case may name any file).

#include "core/toml_reader.hpp"
#include "fuzz_input.hpp"
#include "membrane/io/case_file.hpp"

namespace {
bool affordable(const toml::table& doc) {
  const toml::table* mesh = doc["mesh"].as_table();
  if (!mesh)
    return true;
  if (const auto* type = (*mesh)["type"].as_string(); type && type->get() != "rectangle")
    return false;
  for (const char* k : {"nx", "ny"})
    if (auto n = (*mesh)[k].value<std::int64_t>(); n && *n > 64)
      return false;
  return true;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lamina;
  static const membrane::MaterialSources sources{"/nonexistent/lamina-fuzz-library.toml",
                                                 std::string(LAMINA_SOURCE_DIR) +
                                                     "/materials/catalog.toml"};
  return fuzz::guarded([&] {
    const toml::table doc = core::parseTomlString(fuzz::text(data, size), "fuzz-case.toml");
    if (affordable(doc))
      membrane::buildModel(doc, "fuzz-case.toml", sources);
  });
}
