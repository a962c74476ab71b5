#pragma once
/// @file cell.hpp
/// @brief What the cell bindings give the others: the C++ side of a
/// lamina.Cell (the cell file's spec and the built voxel cell).

#include "python/src/common.hpp"

#include "micro/cell.hpp"
#include "micro/voxel_cell.hpp"

#include <memory>
#include <string>

namespace lamina::python {

/// A lamina.Cell: the spec and the cell, as `homogenize CELL` builds them
/// (Cell.from_file), or a cell whose phase map reads a numpy label array
/// (Cell.from_array; the array is kept alive by the map's borrow).
struct CellData {
  micro::CellSpec spec; ///< phases, size, provenance text (an array cell: its description)
  micro::UnitCell cell; ///< the voxels
  bool copied = false;  ///< from_array: the label array was copied
  std::string source;   ///< the cell file's path, or "<array>"
  /// from_array with a borrowed map: checksum of the labels when the cell
  /// was made (checkUnchanged compares); empty otherwise
  std::string labels_checksum;
};

/// @return the CellData of @p cell, a lamina.Cell; raises lamina.InputError
/// naming @p key for anything else
std::shared_ptr<const CellData> cellData(py::handle cell, const std::string& key = "cell");

/// Raises lamina.InputError when the numpy array a cell borrows was changed
/// since Cell.from_array (its checksum differs): its voxel fractions and
/// provenance would no longer be the cell's, and an id out of range would
/// index past the phases. Nothing to check for a cell that owns its map.
void checkUnchanged(const CellData& cell);

/// @return "fnv1a64:" and the FNV-1a hash of @p cell's phase indices
/// (int32, C order, x slowest)
std::string phaseMapChecksum(const micro::UnitCell& cell);

} // namespace lamina::python
