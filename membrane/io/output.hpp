#pragma once
/// @file output.hpp
/// @brief Result files of a membrane run: the XDMF + HDF5 time series that
/// ParaView opens, and CSV tables streamed line by line.
///
/// Contract (crash safety): the HDF5 file is flushed after every written
/// step and the .xdmf index, which lists only completed steps, is rewritten
/// atomically after each; a crash leaves a valid pair holding the steps
/// written so far. CSV files are written to "<name>.part" and renamed into
/// place by close().

#include "core/hdf5_file.hpp"
#include "membrane/model/mesh.hpp"
#include "membrane/model/structure.hpp"

#include <Eigen/Dense>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace lamina::membrane {

/// Removes from folder @p dir the temporaries that an interrupted atomic
/// write of one of @p files left beside it ("<file>.tmp.<suffix>",
/// core::temporaryPrefix); other files are left alone. A run calls it on its
/// output folder before it writes there.
void removeTemporaries(const std::filesystem::path& dir, const std::vector<std::string>& files);

/// XDMF + HDF5 series: mesh once; per step displacement, velocity, |v|
/// (nodes) and the structure's element fields (the linear model: strain,
/// stress in lamina order). With a deformed geometry each step also holds
/// the current positions X + u, which the step's grid uses, so ParaView
/// draws the deformed surface.
class FieldWriter {
public:
  /// Creates DIR/<stem>.h5 and DIR/<stem>.xdmf for @p mesh.
  FieldWriter(const std::filesystem::path& dir, const std::string& stem, const Mesh& mesh,
              bool deformed_geometry);
  /// Writes the fields of state @p u, @p v at time @p t and the element
  /// fields @p cells, flushes, rewrites the index.
  void write(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
             const std::vector<CellField>& cells);
  /// Reopens the series DIR/<stem>.h5 of an earlier run for appending
  /// after its first @p times.size() steps (later ones, written after the
  /// checkpoint, are removed), with the element-field
  /// layout @p cells of its steps; rewrites the index. Throws lamina::Error
  /// naming the file when it is missing or unreadable, or when one of
  /// those first steps is missing.
  FieldWriter(const std::filesystem::path& dir, const std::string& stem, const Mesh& mesh,
              bool deformed_geometry, const std::vector<double>& times,
              const std::vector<CellField>& cells);
  /// @return number of steps written
  int count() const { return static_cast<int>(times_.size()); }
  /// @return the times of the steps written (s)
  const std::vector<double>& times() const { return times_; }

private:
  void writeIndex() const;
  std::filesystem::path h5_path_, xdmf_path_;
  const Mesh& mesh_;
  bool deformed_;
  std::vector<std::pair<std::string, int>> cells_; // names and components of the element fields
  std::unique_ptr<core::H5File> file_;
  std::vector<double> times_;
};

/// A CSV table streamed to "<path>.part" and renamed to <path> by close().
class CsvWriter {
public:
  /// Opens "<path>.part" and writes @p header (without newline).
  CsvWriter(const std::filesystem::path& path, const std::string& header);
  /// Continues the table of an earlier run: takes "<path>.part" (or <path>,
  /// moved back to "<path>.part"), checks that it starts with @p header and
  /// that its first @p bytes hold the header and exactly @p rows whole rows,
  /// cuts it to @p bytes (rows written after the checkpoint go) and
  /// appends. Throws lamina::Error naming the file.
  CsvWriter(const std::filesystem::path& path, const std::string& header, std::uintmax_t bytes,
            std::uintmax_t rows);
  /// Writes one row of numbers (17 significant digits) and flushes.
  void row(const std::vector<double>& values);
  /// Renames the file into place.
  void close();
  /// @return bytes written so far, header included
  std::uintmax_t bytes() const { return bytes_; }

private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::uintmax_t bytes_ = 0;
  bool closed_ = false;
};

} // namespace lamina::membrane
