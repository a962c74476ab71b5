#pragma once
/// @file atomic_file.hpp
/// @brief Crash-safe file replacement and an advisory inter-process lock.
///
/// writeFileAtomically() writes to a temporary file beside the target, fsyncs
/// it, renames it over the target and fsyncs the directory: a reader sees
/// either the old or the new content, never a half-written file.
///
/// An output only ever replaces a regular file: an existing target that is
/// a directory, a FIFO, a device or a socket (directly or through symlinks)
/// is refused, and checkOutput() also refuses an output that is one of the
/// run's inputs.

#include <filesystem>
#include <string>
#include <vector>

namespace lamina::core {

/// Replaces @p path by @p content atomically (write aside, fsync, rename).
/// A symlink stays a symlink: the file it points to (resolveLinks) is
/// replaced, and an existing file keeps its permission bits (a new one gets
/// 0644). Throws lamina::Error naming the path on failure (also when the
/// target exists and is not a regular file: checkReplaceable); the target
/// is untouched and the temporary removed.
void writeFileAtomically(const std::filesystem::path& path, const std::string& content);

/// @return @p path with every symlink along it followed (also a dangling
/// last link: the file it would create); the path itself when nothing is a
/// link. Throws lamina::Error on a link loop.
std::filesystem::path resolveLinks(const std::filesystem::path& path);

/// Prefix of the temporaries writeFileAtomically() creates beside @p path
/// ("<name>.tmp."); files with it are debris of an interrupted write.
std::string temporaryPrefix(const std::filesystem::path& path);

/// Renames @p from over @p to and fsyncs the directory (the last step of an
/// atomic write done by other means, e.g. an HDF5 file written aside).
/// Refuses (and removes @p from) when @p to exists and is not a regular
/// file (checkReplaceable).
void renameIntoPlace(const std::filesystem::path& from, const std::filesystem::path& to);

/// Throws lamina::Error naming @p path and @p option (e.g. "--out") when
/// @p path exists and is not a regular file once symlinks are followed (a
/// directory, FIFO, character or block device, socket): an output never
/// replaces one. An absent path (or a dangling link) passes.
void checkReplaceable(const std::filesystem::path& path, const std::string& option = "");

/// Throws lamina::Error naming @p out, @p option and the input when @p out
/// is the same file as one of @p inputs (std::filesystem::equivalent: hard
/// links and symlinks included). Empty or absent inputs are skipped.
void checkOutputIsNotInput(const std::filesystem::path& out,
                           const std::vector<std::filesystem::path>& inputs,
                           const std::string& option);

/// checkReplaceable() and checkOutputIsNotInput() of an output file, before
/// a run computes anything.
void checkOutput(const std::filesystem::path& out, const std::vector<std::filesystem::path>& inputs,
                 const std::string& option);

/// Exclusive advisory lock (flock) on "<path>.lock" (symlinks in @p path
/// resolved first, so every name of one file shares one lock), held for the
/// lifetime of the object. Serializes read-modify-write cycles of
/// cooperating processes.
class FileLock {
public:
  /// Blocks until the lock on "<path>.lock" is acquired.
  explicit FileLock(const std::filesystem::path& path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

private:
  int fd_ = -1;
};

} // namespace lamina::core
