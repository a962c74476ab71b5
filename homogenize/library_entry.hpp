#pragma once
/// @file library_entry.hpp
/// @brief From a cell file to library entries: the grid of a unit cell, the
/// entry names of a J sweep, and the Material with its provenance.

#include "homogenize/homogenizer.hpp"
#include "materials/material.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <string>

namespace lamina::homogenize {

/// @return the grid of @p cell (voxel lengths = size / n)
Grid gridOf(const micro::UnitCell& cell);

/// Entry name for matrix state @p J: @p base when the cell has no J sweep
/// (@p sweep false), else base + "-J" + J printed with %g (e.g. "pu-J0.95",
/// "pu-J1").
std::string entryName(const std::string& base, double J, bool sweep);

/// The library entry (kind "homogenized") of one homogenization, with
/// provenance: cell file and its full text, resolution, voxels, volume
/// fractions, J, solver, tolerance, residual and iterations per load case,
/// asymmetry before symmetrizing, symmetry class, lamina version, UTC time,
/// wall time.
materials::Material makeEntry(const std::string& name, const micro::CellSpec& spec,
                              const micro::UnitCell& cell, const Result& result,
                              const Options& options, double J);

/// Solver name written to provenance and docs.
inline constexpr const char* kSolverName =
    "rotated staggered grid (Willot 2015, one-point hex) + FFT-preconditioned CG";

} // namespace lamina::homogenize
