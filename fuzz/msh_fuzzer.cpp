/// @file msh_fuzzer.cpp
/// @brief libFuzzer target: gmsh .msh files through readGmsh (gmsh's own
/// reader, then our checks: z = 0 plane, triangles, regions, node sets).

#include "fuzz_input.hpp"
#include "membrane/model/mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lamina::fuzz::guarded([&] {
    lamina::membrane::readGmsh(
        lamina::fuzz::scratchFile("input.msh", lamina::fuzz::text(data, size)));
  });
}
