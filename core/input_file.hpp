#pragma once
/// @file input_file.hpp
/// @brief The one gate every input file passes before a reader touches it.
///
/// Contract: an input must be a regular file (a symlink to one is fine).
/// FIFOs, character and block devices, directories and sockets are refused
/// with a lamina::Error naming the file and what it is, before anything
/// could block on them or read from them without end. The path is stat()ed
/// first (nothing is opened when it is not a regular file: opening some
/// devices has side effects), then opened with O_NONBLOCK and checked again
/// with fstat() on the open descriptor, so a file swapped for a FIFO between
/// the two cannot block the open. A reader that reads through InputFile
/// reads what was checked; a library that reopens the path by name (HDF5,
/// gmsh) opens it right after the check. Every reader kind has a size bound,
/// checked from the file's size before reading and again while reading.

#include "core/error.hpp"

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace lamina::core {

/// @return what a file of mode @p mode (from stat) is, for messages, when it
/// is not a regular file: "a FIFO (named pipe)", "a directory", ...
const char* fileKindName(mode_t mode);

/// Largest CSV table read (bytes): a pressure history of a million rows fits.
inline constexpr std::uintmax_t kMaxTableBytes = 64u << 20;
/// Largest text mesh (.msh, .geo) read (bytes): more than the node limit of a
/// mesh needs in ASCII; a larger file is refused before it is read.
inline constexpr std::uintmax_t kMaxMeshBytes = std::uintmax_t{16} << 30;
/// Largest image file read (bytes); the memory an image takes is checked
/// against the machine as well (a crop or down-sampling reduces that).
inline constexpr std::uintmax_t kMaxImageBytes = std::uintmax_t{256} << 30;
/// Largest HDF5 input (checkpoint, side file) opened (bytes).
inline constexpr std::uintmax_t kMaxHdf5Bytes = std::uintmax_t{1} << 40;

/// An input file opened for reading after the regular-file check.
class InputFile {
public:
  /// Opens @p path for reading. Throws lamina::Error naming the file and
  /// @p what ("pressure table", "mesh file"...) when it is missing or
  /// unreadable, is not a regular file, or holds more than @p max_bytes.
  /// @param where context of the error; its file defaults to @p path
  InputFile(const std::filesystem::path& path, const std::string& what, std::uintmax_t max_bytes,
            ErrorContext where = {});
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// @return the open descriptor (owned: closed with this object)
  int fd() const { return fd_; }
  /// @return the size in bytes when it was opened
  std::uintmax_t size() const { return size_; }
  /// Reads the whole file (at most the bound given at construction: a file
  /// that grew beyond it while read is refused). Checks the memory first.
  std::string readAll();
  /// Reads exactly @p bytes at @p offset into @p data; a file shorter than
  /// that (cut while read) is an error naming it.
  void readAt(std::uint64_t offset, void* data, std::size_t bytes) const;

private:
  /// "the WHAT" (and the path when the error's context names another file)
  std::string subject() const;
  /// Closes the descriptor and throws lamina::Error "subject() MESSAGE".
  [[noreturn]] void fail(const std::string& message) const;

  std::filesystem::path path_;
  std::string what_;
  std::uintmax_t max_bytes_;
  ErrorContext where_;
  int fd_ = -1;
  std::uintmax_t size_ = 0;
};

/// Checks that @p path is a regular file (following symlinks) of at most
/// @p max_bytes, opening it without blocking; @return its size. Throws
/// lamina::Error as InputFile does.
std::uintmax_t checkRegularInput(const std::filesystem::path& path, const std::string& what,
                                 std::uintmax_t max_bytes, ErrorContext where = {});

/// @return the whole content of @p path, read after the checks of
/// InputFile with the bound @p max_bytes.
std::string readWholeFile(const std::filesystem::path& path, std::uintmax_t max_bytes,
                          const std::string& what, ErrorContext where = {});

} // namespace lamina::core
