#pragma once
/// @file hdf5_file.hpp
/// @brief Thin RAII wrapper over the HDF5 C API: files, groups, datasets of
/// doubles and integers, string and number attributes. All failures throw
/// lamina::Error naming the file and the dataset.

#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lamina::core {

/// Owns one hid_t and closes it with the matching H5*close function.
class H5Handle {
public:
  using Closer = herr_t (*)(hid_t);
  H5Handle() = default;
  /// Takes ownership of @p id (must be valid, >= 0), closed with @p closer.
  H5Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~H5Handle() { reset(); }
  H5Handle(H5Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = -1; }
  H5Handle& operator=(H5Handle&& o) noexcept;
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  /// @return the raw id (-1 if empty)
  hid_t id() const { return id_; }
  /// Closes the handle now.
  void reset();

private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

/// @return HDF5's own description of why the last call failed when it says
/// the file is truncated ("truncated file: eof = ..., stored_eof = ..."),
/// else "" (the rest of its error stack names internals, not the input).
std::string hdf5TruncationReason();

/// An HDF5 file opened for writing (created/truncated) or reading.
class H5File {
public:
  enum class Mode { Create, ReadOnly, ReadWrite };
  /// Opens or creates @p path. Throws lamina::Error on failure.
  /// With Mode::Create and @p userblock > 0 (a power of two, >= 512), the
  /// file starts with that many bytes HDF5 leaves alone (its user block),
  /// for the writer's own header.
  H5File(const std::filesystem::path& path, Mode mode, std::uint64_t userblock = 0);

  /// Creates group @p name (and its parents) if missing.
  void createGroup(const std::string& name);
  /// Writes a dataset of doubles with shape @p dims (row-major, C order).
  void writeDoubles(const std::string& name, const double* data,
                    const std::vector<std::uint64_t>& dims);
  /// Writes a dataset of 32-bit integers with shape @p dims.
  void writeInts(const std::string& name, const std::int32_t* data,
                 const std::vector<std::uint64_t>& dims);
  /// Writes a dataset of unsigned 64-bit integers (e.g. gmsh tags) with shape @p dims.
  void writeUInt64s(const std::string& name, const std::uint64_t* data,
                    const std::vector<std::uint64_t>& dims);
  /// Reads a dataset of doubles; @p dims receives its shape. Throws
  /// lamina::Error naming the file and dataset unless it stores numbers of
  /// the kind asked for (float here, integer below) of at most 8 bytes each.
  std::vector<double> readDoubles(const std::string& name, std::vector<std::uint64_t>& dims) const;
  /// Reads a dataset of integers; @p dims receives its shape.
  std::vector<std::int32_t> readInts(const std::string& name,
                                     std::vector<std::uint64_t>& dims) const;
  /// @return whether the object (dataset or group) @p name exists.
  bool exists(const std::string& name) const;
  /// Removes the object (dataset or group, with its content) @p name if it
  /// exists; HDF5 keeps the file's size, the object is no longer in it.
  void remove(const std::string& name);
  /// Attaches a string attribute to object @p object ("/" for the file).
  void writeAttribute(const std::string& object, const std::string& attr, const std::string& value);
  /// Attaches a double attribute to object @p object.
  void writeAttribute(const std::string& object, const std::string& attr, double value);
  /// Reads a string attribute.
  std::string readStringAttribute(const std::string& object, const std::string& attr) const;
  /// Flushes buffered data to disk (so a crash keeps what was written).
  void flush();
  /// @return the path given at construction
  const std::filesystem::path& path() const { return path_; }

private:
  [[noreturn]] void fail(const std::string& what, const std::string& object) const;
  void write(const std::string& name, hid_t type, const void* data,
             const std::vector<std::uint64_t>& dims);
  std::filesystem::path path_;
  H5Handle file_;
};

} // namespace lamina::core
