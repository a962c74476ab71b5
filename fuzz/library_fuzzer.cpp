/// @file library_fuzzer.cpp
/// @brief libFuzzer target: the materials library reader. Property: what
/// parses serializes to text that parses back to the same entries.

#include "fuzz_input.hpp"
#include "materials/library.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using lamina::materials::Library;
  return lamina::fuzz::guarded([&] {
    const auto entries = Library::parse(lamina::fuzz::text(data, size), "fuzz-library.toml");
    const auto back = Library::parse(Library::serialize(entries), "fuzz-library (serialized)");
    if (back.size() != entries.size())
      std::abort(); // a round trip lost or invented entries
    for (const auto& [name, m] : entries)
      if (!back.count(name) || !(back.at(name).C.matrix() == m.C.matrix()) ||
          back.at(name).density != m.density)
        std::abort(); // a round trip changed a number (17 digits must be exact)
  });
}
