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
#include <system_error>

namespace lamina::fuzz {

/// @return the fuzz input as a string
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// The folder private to this process under the system temporary folder
/// (TMPDIR) that scratchFile writes into; removed when the fuzzer exits
/// normally (a crash leaves it for the reproducer's inspection).
struct ScratchDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("lamina-fuzz-" + std::to_string(::getpid()));
  ScratchDir() { std::filesystem::create_directories(path); }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

/// Writes @p content to a file named @p name in the process's ScratchDir and
/// @return its path (readers that only take paths). Nothing is written
/// anywhere else.
inline std::filesystem::path scratchFile(const std::string& name, const std::string& content) {
  static const ScratchDir dir;
  const auto p = dir.path / name;
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
