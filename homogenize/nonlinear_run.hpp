#pragma once
/// @file nonlinear_run.hpp
/// @brief The nonlinear modes of the `homogenize` program: a cell under a
/// macroscopic strain-rate history (CSV of the effective and per-phase
/// responses, optional fields), and rate-dependent effective tangents
/// written as library entries.

#include "homogenize/nonlinear_homogenizer.hpp"
#include "materials/library.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lamina::homogenize {

/// A loading path of the cell (the vocabulary of `materials drive`).
struct PathSpec {
  materials::DrivePath path = materials::DrivePath::UniaxialStrain; ///< strain path
  double rate = 1e4;                                                ///< driven strain rate (1/s)
  double to = 0.1;                                                  ///< final driven strain
  int steps = 100;                                                  ///< load steps per leg
  bool unload = false; ///< back to zero at the same rate
};

/// @return the law of every phase of @p spec (Phase::model); throws
/// lamina::Error for a void phase (nonlinear runs do not handle pores)
std::vector<materials::LawPtr> phaseLaws(const micro::CellSpec& spec);

/// @return the files runPath() writes for @p out (none when empty): @p out,
/// OUT_STEM-phases.csv and, with @p fields, OUT_STEM-fields.h5 and .xdmf
std::vector<std::filesystem::path> pathOutputs(const std::filesystem::path& out, bool fields);

/// Runs @p path on @p cell. Writes, if @p out is not empty: @p out (the
/// header of `materials drive` plus newton,krylov,residual,wall_s; one row
/// per step with t = 0 first) and OUT_STEM-phases.csv (t,phase and the
/// per-phase average strain and stress). For each step listed in
/// @p field_steps, the strain and stress fields go to OUT_STEM-fields.h5
/// (datasets /step_N/eps_xx ... /step_N/sig_xz, each N1 x N2 x N3, C order)
/// with an XDMF file beside it. @p report is called after each step; a
/// core::ProgressLine "path steps" (quiet: its observer only) follows the
/// steps. Under an InterruptGuard a signal stops the run (lamina::Interrupted)
/// within a CG iteration or after a step, before any output is written.
std::vector<StepResult> runPath(const micro::CellSpec& spec, const micro::UnitCell& cell,
                                const PathSpec& path, const NonlinearOptions& options,
                                const std::filesystem::path& out,
                                const std::vector<int>& field_steps,
                                const std::function<void(const StepResult&)>& report = {});

/// What a rate-dependent tangent entry is.
struct TangentSpec {
  std::vector<double> rates; ///< strain rates (1/s); inf allowed (instantaneous)
  double strain = 0;         ///< driven strain of the state (0: virgin state)
  double increment = 1e-3;   ///< strain increment the tangent is for: dt = increment / rate
  PathSpec path;             ///< path that reaches the state (rate replaced per entry)
};

/// Entry name for @p rate: base + "-R" + rate printed with %g ("pu-R100000",
/// "pu-R1e+06", "pu-Rinf").
std::string rateEntryName(const std::string& base, double rate);

/// Checks @p tangent and the entry names of its rates before anything is
/// computed: every rate in [kMinRate, kMaxRate] or inf (finite with a
/// strain), the strain and increment, valid names that do not collide with
/// each other nor (unless @p overwrite) with entries of @p library. Throws
/// lamina::Error naming the argument. @return the entry names, one per rate.
std::vector<std::string> checkTangentSpec(const std::string& base, const TangentSpec& tangent,
                                          const materials::Library& library, bool overwrite);

/// For every rate: drives the cell along the path at that rate to the
/// strain, takes the effective consistent tangent of an increment over
/// dt = increment / rate (NonlinearHomogenizer::effectiveTangent), and adds
/// it to @p library as a "homogenized" entry with its provenance (rate,
/// strain, path, increment, dt, the cell and the solver). checkTangentSpec
/// runs first; the entries are added in one transaction (all or none) once
/// all are computed, then @p report is called for each.
void addTangentEntries(const micro::CellSpec& spec, const micro::UnitCell& cell,
                       const std::string& base, const TangentSpec& tangent,
                       const NonlinearOptions& options, materials::Library& library, bool overwrite,
                       const std::function<void(const materials::Material&)>& report = {});

} // namespace lamina::homogenize
