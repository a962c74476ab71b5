/// @file catalog_fuzzer.cpp
/// @brief libFuzzer target: the catalog of base materials (a TOML file).

#include "fuzz_input.hpp"
#include "materials/catalog.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lamina::fuzz::guarded([&] {
    const lamina::materials::Catalog catalog(
        lamina::fuzz::scratchFile("catalog.toml", lamina::fuzz::text(data, size)));
    (void)catalog;
  });
}
