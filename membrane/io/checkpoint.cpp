#include "membrane/io/checkpoint.hpp"

#include "core/atomic_file.hpp"
#include "core/checksum.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "core/toml_reader.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <iterator>
#include <sstream>
#include <unistd.h>

namespace lamina::membrane {

namespace {

constexpr const char* kFormat = "lamina membrane checkpoint 2";

/// The checkpoint's own header: HDF5's user block, which holds the
/// checksum of every byte after it, so that a damaged container is refused
/// before HDF5 parses it (HDF5 1.10 reads freed memory on some corrupt
/// attribute messages, found by fuzz/checkpoint_fuzzer.cpp).
constexpr std::uint64_t kHeaderBytes = 512;
constexpr const char* kHeaderTag = "lamina membrane checkpoint, bytes from 512: ";

/// Writes the header of the closed checkpoint @p path (its checksum).
void writeHeader(const std::filesystem::path& path) {
  const std::string header = kHeaderTag + core::fileChecksum(path, "checkpoint", kHeaderBytes) +
                             "\n";
  const int fd = ::open(path.c_str(), O_WRONLY);
  const bool ok = fd >= 0 && ::pwrite(fd, header.data(), header.size(), 0) ==
                                 static_cast<ssize_t>(header.size());
  if (fd >= 0)
    ::close(fd);
  if (!ok)
    throw Error("cannot write the checkpoint's header", {path.string(), 0, ""});
}

/// Throws unless the header of @p path holds the checksum of its bytes.
void checkHeader(const std::filesystem::path& path, const ErrorContext& where) {
  std::string sum, header;
  try {
    sum = core::fileChecksum(path, "checkpoint", kHeaderBytes);
    header.assign(std::strlen(kHeaderTag) + sum.size(), '\0');
    const core::InputFile in(path, "checkpoint", core::kMaxHdf5Bytes);
    in.readAt(0, header.data(), header.size());
  } catch (const Error& e) {
    throw Error("checkpoint is unreadable (truncated, corrupt or not a checkpoint): " +
                    e.message(),
                where);
  }
  if (header.compare(0, std::strlen(kHeaderTag), kHeaderTag) != 0)
    throw Error("checkpoint is unreadable (truncated, corrupt, of an older lamina or not a "
                "checkpoint): no lamina checkpoint header",
                where);
  if (header.compare(std::strlen(kHeaderTag), sum.size(), sum) != 0)
    throw Error("checkpoint is unreadable (truncated or corrupt): its bytes do not match the "
                "checksum in its header",
                where);
}

std::string checksum(const History& data) {
  core::Fnv1a f;
  for (const auto& [key, v] : data) {
    f.add(key);
    const auto n = static_cast<std::uint64_t>(v.size());
    f.add(&n, sizeof n);
    f.add(v.data(), sizeof(double) * static_cast<std::size_t>(v.size()));
  }
  return f.hex();
}

void fsyncFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  const bool ok = fd >= 0 && ::fsync(fd) == 0;
  if (fd >= 0)
    ::close(fd);
  if (!ok)
    throw Error("cannot sync the checkpoint to disk", {path.string(), 0, ""});
}

} // namespace

std::filesystem::path checkpointPath(const std::filesystem::path& dir) {
  return dir / "checkpoint.h5";
}

void writeCheckpoint(const std::filesystem::path& path, const Checkpoint& checkpoint) {
  const std::filesystem::path tmp =
      path.parent_path() / (core::temporaryPrefix(path) + std::to_string(::getpid()));
  try {
    {
      core::H5File f(tmp, core::H5File::Mode::Create, kHeaderBytes);
      std::string keys;
      std::vector<double> sizes;
      f.createGroup("/data");
      for (const auto& [key, v] : checkpoint.data) {
        keys += key + "\n";
        sizes.push_back(static_cast<double>(v.size()));
        if (v.size())
          f.writeDoubles("/data/" + key, v.data(), {static_cast<std::uint64_t>(v.size())});
      }
      f.writeDoubles("/sizes", sizes.data(), {static_cast<std::uint64_t>(sizes.size())});
      f.writeAttribute("/", "format", kFormat);
      f.writeAttribute("/", "case", checkpoint.case_name);
      f.writeAttribute("/", "case_digest", checkpoint.case_digest);
      f.writeAttribute("/", "keys", keys);
      f.writeAttribute("/", "checksum", checksum(checkpoint.data));
      f.flush();
    } // closed
    writeHeader(tmp);
    fsyncFile(tmp);
    core::renameIntoPlace(tmp, path);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

Checkpoint readCheckpoint(const std::filesystem::path& path) {
  const ErrorContext where{path.string(), 0, ""};
  if (!std::filesystem::is_regular_file(path))
    throw Error("no checkpoint here (a run writes one with output.checkpoint_every or when "
                "interrupted)",
                where);
  Checkpoint c;
  std::string stored_sum;
  checkHeader(path, where); // before HDF5 parses a byte of it
  try {
    const core::H5File f(path, core::H5File::Mode::ReadOnly);
    if (f.readStringAttribute("/", "format") != kFormat)
      throw Error("not a membrane checkpoint (format '" + f.readStringAttribute("/", "format") +
                      "')",
                  where);
    c.case_name = f.readStringAttribute("/", "case");
    c.case_digest = f.readStringAttribute("/", "case_digest");
    stored_sum = f.readStringAttribute("/", "checksum");
    std::istringstream keys(f.readStringAttribute("/", "keys"));
    std::vector<std::uint64_t> dims;
    const std::vector<double> sizes = f.readDoubles("/sizes", dims);
    std::string key;
    std::size_t k = 0;
    for (; std::getline(keys, key); ++k) {
      if (k >= sizes.size())
        throw Error("more entries than sizes", where);
      constexpr double kMaxSize = 9007199254740992.0; // 2^53: every integer below is a double
      if (!(sizes[k] >= 0 && sizes[k] <= kMaxSize && sizes[k] == std::floor(sizes[k])))
        throw Error("entry '" + key + "' has the size " + core::formatShort(sizes[k]), where);
      Eigen::VectorXd v;
      if (sizes[k] > 0) {
        const std::vector<double> x = f.readDoubles("/data/" + key, dims);
        if (static_cast<double>(x.size()) != sizes[k])
          throw Error("entry '" + key + "' has " + std::to_string(x.size()) + " values, " +
                          std::to_string(static_cast<long>(sizes[k])) + " expected",
                      where);
        v = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
      }
      if (!c.data.emplace(key, std::move(v)).second)
        throw Error("entry '" + key + "' appears twice", where);
    }
    if (k != sizes.size())
      throw Error("more sizes than entries", where);
  } catch (const Error& e) {
    throw Error("checkpoint is unreadable (truncated, corrupt or not a checkpoint): " +
                    std::string(e.what()),
                where);
  }
  if (checksum(c.data) != stored_sum)
    throw Error("checkpoint is corrupt: its checksum does not match its content", where);
  for (const auto& [key, v] : c.data) // every saved quantity is finite (a diverged run saves none)
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]))
        throw Error("checkpoint entry '" + key + "' value " + std::to_string(i) + " is not finite",
                    where);
  return c;
}

std::string caseDigest(const std::filesystem::path& case_file,
                       const std::vector<std::string>& overrides) {
  const std::string text = core::readWholeFile(case_file, core::kMaxTomlBytes, "case file");
  core::Fnv1a f;
  f.add(text);
  for (const auto& o : overrides)
    if (o.rfind("output.checkpoint_every", 0) != 0)
      f.add(o);
  return f.hex();
}

} // namespace lamina::membrane
