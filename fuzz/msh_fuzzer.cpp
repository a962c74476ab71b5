/// @file msh_fuzzer.cpp
/// @brief libFuzzer target: gmsh .msh files through readGmsh (checkMshFile, gmsh's own
/// reader, then our checks: z = 0 plane, triangles, regions, node sets).
/// gmsh reads in this process (GmshProbe::kInProcess), not in the forked
/// child that readGmsh uses by default: an input that passes checkMshFile
/// and still crashes gmsh is a gap in the check and must be a finding.

#include "fuzz_input.hpp"
#include "membrane/io/gmsh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lamina::fuzz::guarded([&] {
    lamina::membrane::readGmsh(
        lamina::fuzz::scratchFile("input.msh", lamina::fuzz::text(data, size)),
        lamina::membrane::GmshProbe::kInProcess);
  });
}
