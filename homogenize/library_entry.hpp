#pragma once
/// @file library_entry.hpp
/// @brief From a cell file to library entries: the grid of a unit cell, the
/// entry names of a J sweep, and the Material with its provenance.

#include "homogenize/dispersion.hpp"
#include "homogenize/homogenizer.hpp"
#include "materials/library.hpp"
#include "materials/material.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
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
/// wall time. With @p dispersion (a cell with a size in metres) the entry
/// also holds `dispersion` (zeta^2 D_lin, kg/m), `cell_size` (m) and the
/// least-squares residuals of eq. 39 in its provenance.
materials::Material makeEntry(const std::string& name, const micro::CellSpec& spec,
                              const micro::UnitCell& cell, const Result& result,
                              const Options& options, double J,
                              const Dispersion* dispersion = nullptr);

/// Refuses (lamina::Error naming @p spec's file and `phases`), for a
/// library entry, the singular C of a porous cell whose solid does not span
/// it (void layers, solid inclusions in a void matrix): a library entry's C
/// is positive definite.
void checkPercolates(const micro::CellSpec& spec, const materials::Stiffness& C);

/// One homogenized entry: its name, matrix state and result.
struct EntryResult {
  std::string name;                     ///< library entry name
  double J = 1.0;                       ///< matrix state of the gvbo phase
  Result result;                        ///< C, density, diagnostics
  std::optional<Dispersion> dispersion; ///< micro-inertia (cells with a size in metres)
};

/// Homogenizes @p cell at matrix state @p J; with a physical cell size
/// (spec.physical_size) also its dispersion tensor from the same solves.
/// Distributed (@p dist): every rank calls this; rank 0 holds @p cell's
/// whole map, builds the voxel materials, scatters them and gets the
/// dispersion. Throws lamina::Error for a cell with a size and a void phase
/// (the dispersion tensor needs the displacement inside the pores, which the
/// cell problem leaves undetermined).
EntryResult homogenizeCell(const micro::CellSpec& spec, const micro::UnitCell& cell,
                           const std::string& name, double J, const Options& options,
                           const Distribution* dist = nullptr);

/// Homogenizes @p cell at every J state of @p spec (entryName rule) and adds
/// the entries to @p library in one transaction (all or none). Checks all
/// names before computing: an invalid name, two states whose names collide
/// and an existing entry (unless @p overwrite) are errors. @p report, if
/// set, is called for each entry once all are committed. A porous cell
/// whose C comes out singular (its solid does not span the cell) is an
/// error: a library entry's C is positive definite.
/// Distributed (@p dist): every rank calls this; rank 0 holds the cell's
/// whole phase map and scatters it, and alone writes the side files and the
/// library and calls @p report.
std::vector<EntryResult>
homogenizeIntoLibrary(const micro::CellSpec& spec, const micro::UnitCell& cell,
                      const std::string& base, const Options& options, materials::Library& library,
                      bool overwrite, const std::function<void(const EntryResult&)>& report = {},
                      const Distribution* dist = nullptr);

/// @return @p library as the `--json` outputs name it ("library"): the
/// absolute path, normalized, of the file that received the entry
std::string libraryJsonPath(const std::filesystem::path& library);

/// The `--json` summary of an entry: name, library (the absolute path of
/// @p library, the file that received it), C (6x6, Pa, lamina order),
/// density, iterations (6), residual, voxels, volume_fraction (all
/// inclusions), phase_fractions, asymmetry, symmetry, J, wall_s; with
/// micro-inertia also dispersion (6x6, kg/m), cell_size (m) and
/// dispersion_residuals (eq. 39 least squares, per load case).
nlohmann::json toJson(const EntryResult& e, const std::filesystem::path& library);

/// @return the current UTC time as ISO 8601 (provenance "time")
std::string utcNow();

/// The provenance every homogenized entry (linear or nonlinear) starts with:
/// program (@p program), version, time (UTC), cell_file, cell_text,
/// cell_overrides (the --set KEY=VALUE over cell_text; only when given) and
/// resolution of @p cell.
toml::table cellProvenance(const std::string& program, const micro::CellSpec& spec,
                           const micro::UnitCell& cell);

/// @return the volume-averaged density of @p cell (kg/m^3): the phase
/// densities of @p spec weighted by the cell's voxel fractions (cut voxels
/// split by their fractions)
double meanDensity(const micro::CellSpec& spec, const micro::UnitCell& cell);

/// Solver name written to provenance and docs.
inline constexpr const char* kSolverName =
    "rotated staggered grid (Willot 2015, one-point hex) + FFT-preconditioned CG";

/// Dispersion method written to provenance.
inline constexpr const char* kDispersionMethod =
    "D_lin of GVBO chapter eqs. 38-39: h = H + least-squares periodic solution of the density "
    "term (FFT, rotated-grid gradient); zeta^2 D = rho <h h> (trilinear interpolant)";

} // namespace lamina::homogenize
