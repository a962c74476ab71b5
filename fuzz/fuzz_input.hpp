#pragma once
/// @file fuzz_input.hpp
/// @brief What every fuzz target shares: the input as text, a private
/// temporary file for the readers that take a path, and the rule that a
/// lamina::Error (a clean refusal) is a pass while anything else escaping
/// is a finding.

#include "core/error.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace lamina::fuzz {

/// @return the fuzz input as a string
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Writes @p content to a file named @p name in a folder private to this
/// process and @return its path (readers that only take paths).
inline std::filesystem::path scratchFile(const std::string& name, const std::string& content) {
  static const std::filesystem::path dir = [] {
    const auto d =
        std::filesystem::temp_directory_path() / ("lamina-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto p = dir / name;
  std::ofstream(p, std::ios::binary | std::ios::trunc) << content;
  return p;
}

/// Runs @p f: a lamina::Error is the expected answer to bad input. Any other
/// exception escapes and libFuzzer reports it (an uncaught exception aborts).
template <typename F>
int guarded(F&& f) {
  try {
    f();
  } catch (const Error&) {
  }
  return 0;
}

} // namespace lamina::fuzz
