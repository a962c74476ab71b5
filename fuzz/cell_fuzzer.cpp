/// @file cell_fuzzer.cpp
/// @brief libFuzzer target: unit-cell files, read and built (placement and
/// voxelization) at 8^3 voxels so that one input runs in milliseconds;
/// larger resolutions are the malformed tests' business. Random placement
/// is capped at 100 attempts per inclusion (the default is 200,000): a
/// group that cannot be placed is then refused in well under a second
/// instead of ~10 s (Release; minutes under ASan), which libFuzzer would
/// report as a timeout; the refusal itself is the same code path.

#include "fuzz_input.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <algorithm>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lamina::micro;
  static const std::string catalog = std::string(LAMINA_SOURCE_DIR) + "/materials/catalog.toml";
  return lamina::fuzz::guarded([&] {
    CellSpec spec =
        readCellString(lamina::fuzz::text(data, size), "fuzz-cell.toml", lazyCatalog(catalog));
    for (InclusionGroup& g : spec.groups)
      g.max_attempts = std::min(g.max_attempts, 100);
    buildCell(spec, {8, 8, 8});
  });
}
