#pragma once
/// @file checksum.hpp
/// @brief FNV-1a (64 bits): a checksum against corruption and accidental
/// edits (a truncated or changed file, an array written over), not a
/// cryptographic hash. Used by checkpoints (over their arrays) and by the
/// library (over side files).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace lamina::core {

/// Incremental FNV-1a, 64 bits.
class Fnv1a {
public:
  /// Adds @p bytes bytes at @p data.
  void add(const void* data, std::size_t bytes);
  /// Adds the characters of @p s and its terminator (so "a","b" differs from "ab").
  void add(const std::string& s) { add(s.data(), s.size() + 1); }
  /// @return the hash as 16 lower-case hex digits
  std::string hex() const;

private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

/// @return "fnv1a64:" and the 16 hex digits of FNV-1a over the bytes of
/// file @p path (read in blocks through the input-file gate:
/// input_file.hpp); throws lamina::Error naming @p what and the file if it
/// is not a readable regular file.
/// @param from the first byte covered (bytes before it are left out; a
/// file shorter than that is an error)
std::string fileChecksum(const std::filesystem::path& path, const std::string& what = "file",
                         std::uint64_t from = 0);

} // namespace lamina::core
