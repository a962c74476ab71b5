/// @file cell_fuzzer.cpp
/// @brief libFuzzer target: unit-cell files, read and built (placement and
/// voxelization) at 8^3 voxels so that one input runs in milliseconds;
/// larger resolutions are the malformed tests' business.

#include "fuzz_input.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lamina::micro;
  static const std::string catalog = std::string(LAMINA_SOURCE_DIR) + "/materials/catalog.toml";
  return lamina::fuzz::guarded([&] {
    const CellSpec spec =
        readCellString(lamina::fuzz::text(data, size), "fuzz-cell.toml", lazyCatalog(catalog));
    buildCell(spec, {8, 8, 8});
  });
}
