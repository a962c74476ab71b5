#pragma once
/// @file checkpoint.hpp
/// @brief Checkpoints of `membrane run`: one HDF5 file, DIR/checkpoint.h5,
/// holding a History (named arrays of doubles, stored bit for bit) and the
/// digest of the case that wrote it.
///
/// Layout: attributes "format" ("lamina membrane checkpoint 1"), "case",
/// "case_digest", "keys" (the entry names, one per line) and "checksum"
/// (FNV-1a 64 of the names and bytes of all entries, hex); the dataset
/// "/sizes" (values per entry, in key order) and "/data/<key>" for each
/// non-empty entry. The file is written beside its place, fsynced and
/// renamed over the previous checkpoint: a reader sees the old or the new
/// checkpoint, never a torn one.

#include "membrane/integrators/time_integrator.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace lamina::membrane {

/// What one checkpoint file holds.
struct Checkpoint {
  std::string case_name;   ///< the case's name (for messages)
  std::string case_digest; ///< identifies the case (caseDigest())
  History data;            ///< the simulation's and the run's history
};

/// @return the checkpoint file of output folder @p dir (DIR/checkpoint.h5)
std::filesystem::path checkpointPath(const std::filesystem::path& dir);

/// Writes @p checkpoint to @p path atomically (temporary beside it, fsync,
/// rename). Throws lamina::Error naming the file on failure.
void writeCheckpoint(const std::filesystem::path& path, const Checkpoint& checkpoint);

/// Reads the checkpoint @p path. Throws lamina::Error naming the file when
/// it is missing, unreadable, truncated, not a checkpoint, when its
/// checksum does not match its content, or when a value is not finite. What
/// the values mean is checked by their readers (Simulation::restore, the run).
Checkpoint readCheckpoint(const std::filesystem::path& path);

/// @return a digest (16 hex digits) of the bytes of case file @p case_file
/// and of the --set @p overrides, except those of output.checkpoint_every
/// (which do not change the results). Throws lamina::Error when the file
/// cannot be read.
std::string caseDigest(const std::filesystem::path& case_file,
                       const std::vector<std::string>& overrides);

} // namespace lamina::membrane
