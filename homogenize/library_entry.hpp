#pragma once
/// @file library_entry.hpp
/// @brief From a cell file to library entries: the grid of a unit cell, the
/// entry names of a J sweep, and the Material with its provenance.

#include "homogenize/homogenizer.hpp"
#include "materials/library.hpp"
#include "materials/material.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

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

/// One homogenized entry: its name, matrix state and result.
struct EntryResult {
  std::string name; ///< library entry name
  double J = 1.0;   ///< matrix state of the gvbo phase
  Result result;    ///< C, density, diagnostics
};

/// Homogenizes @p cell at every J state of @p spec (entryName rule) and adds
/// each entry to @p library. Checks all names first: an existing entry is an
/// error unless @p overwrite. @p report, if set, is called after each entry.
std::vector<EntryResult>
homogenizeIntoLibrary(const micro::CellSpec& spec, const micro::UnitCell& cell,
                      const std::string& base, const Options& options, materials::Library& library,
                      bool overwrite, const std::function<void(const EntryResult&)>& report = {});

/// The `--json` summary of an entry: name, C (6x6, Pa, lamina order),
/// density, iterations (6), residual, voxels, volume_fraction (all
/// inclusions), phase_fractions, asymmetry, symmetry, J, wall_s.
nlohmann::json toJson(const EntryResult& e);

/// Solver name written to provenance and docs.
inline constexpr const char* kSolverName =
    "rotated staggered grid (Willot 2015, one-point hex) + FFT-preconditioned CG";

} // namespace lamina::homogenize
