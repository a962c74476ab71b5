#pragma once
/// @file phase_map_io.hpp
/// @brief Phase maps on disk: HDF5 dataset /phases (int32, N1 x N2 x N3,
/// C order, x slowest) with an XDMF file that ParaView opens.

#include "micro/voxel_cell.hpp"

#include <filesystem>

namespace lamina::micro {

/// Writes @p cell's phase map to @p h5 (dataset "/phases", attributes
/// "size_x/y/z" and "phase_names") and an XDMF file beside it (same stem,
/// .xdmf). Both are written aside and renamed into place.
/// @param phase_names names of the phases, in index order, joined for the attribute
void writePhaseMap(const UnitCell& cell, const std::vector<std::string>& phase_names,
                   const std::filesystem::path& h5);

/// Reads "/phases" from @p h5 into a UnitCell (n, phase, voxel fractions; the
/// size is left at 1: effective moduli do not depend on it). @p phase_count is the number of phases
/// expected; an index outside [0, phase_count) is an error naming the file.
UnitCell readPhaseMap(const std::filesystem::path& h5, int phase_count);

} // namespace lamina::micro
