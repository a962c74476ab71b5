#pragma once
/// @file atomic_file.hpp
/// @brief Crash-safe file replacement and an advisory inter-process lock.
///
/// writeFileAtomically() writes to a temporary file beside the target, fsyncs
/// it, renames it over the target and fsyncs the directory: a reader sees
/// either the old or the new content, never a half-written file.

#include <filesystem>
#include <string>

namespace lamina::core {

/// Replaces @p path by @p content atomically (write aside, fsync, rename).
/// Throws lamina::Error naming the path on failure; the target is untouched.
void writeFileAtomically(const std::filesystem::path& path, const std::string& content);

/// Renames @p from over @p to and fsyncs the directory (the last step of an
/// atomic write done by other means, e.g. an HDF5 file written aside).
void renameIntoPlace(const std::filesystem::path& from, const std::filesystem::path& to);

/// Exclusive advisory lock (flock) on "<path>.lock", held for the lifetime of
/// the object. Serializes read-modify-write cycles of cooperating processes.
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
