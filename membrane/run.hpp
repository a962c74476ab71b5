#pragma once
/// @file run.hpp
/// @brief `membrane run`: set up, step, write the outputs of one case.
///
/// Writes into the output folder: <name>.xdmf + <name>.h5 (fields),
/// probes.csv (t,<probe>_ux,_uy,_uz,_vx,_vy,_vz,...), energy.csv,
/// reactions.csv (per constraint set, when there are constraints),
/// checkpoint.h5 (every output.checkpoint_every steps, on SIGINT/SIGTERM
/// and at RunOptions::stop_at_step; io/checkpoint.hpp) and summary.json
/// (written atomically last). On divergence the last finite
/// state is written, summary.json records the message and
/// lamina::DivergenceError is rethrown (exit code 3).

#include "membrane/system/model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace lamina::membrane {

/// Options of one run.
struct RunOptions {
  std::filesystem::path out_dir = "."; ///< output folder (created)
  bool quiet = false;                  ///< no progress line
  /// Continue the run whose outputs and checkpoint.h5 are in out_dir, from
  /// its checkpoint: the outputs are cut back to the checkpoint's step and
  /// appended to, and the result is bit-identical to an uninterrupted run.
  bool restart = false;
  /// Stop after this step (counted from t = 0) with a checkpoint, as for an
  /// interrupt but exiting normally (0: run to t_end).
  long stop_at_step = 0;
  /// A stop_at_step this run (a restart) is already past is not refused: the
  /// run goes on to t_end (the first of a compare_without_drag case's two
  /// runs, whose second run then stops there).
  bool stop_may_be_past = false;
  /// The folder the interrupt's message names for `--restart` (empty:
  /// out_dir; a compare_without_drag case's runs name the case's folder).
  std::filesystem::path restart_folder;
  /// Identifies the case in checkpoints (caseDigest() of the case file and
  /// --set options); a restart refuses a checkpoint with another digest.
  /// Empty: the model's name.
  std::string case_digest;
};

/// Runs @p model and @return the summary object (also written to summary.json).
nlohmann::json runModel(const Model& model, const RunOptions& options);

/// `membrane run`: runModel, or for `compare_without_drag = true` two runs
/// (DIR/with-drag, DIR/without-drag) and DIR/summary.json = the with-drag
/// summary plus "drag_comparison" {with_drag, without_drag: {max_abs_w,
/// peak_reaction (largest per-set peak), peak_total_reaction (peak of the
/// magnitude of the sum of all reactions, springs included), max_speed}}.
///
/// Each of the two runs checkpoints in its own folder. A run that stops
/// (signal, stop_at_step, divergence) ends the case: DIR/summary.json is
/// then that run's summary plus "stopped_run" (its folder's name). A
/// restart (options.restart, out_dir = DIR) continues the run with drag
/// unless its summary.json records a run that ended, then runs the one
/// without drag from t = 0; or, the run with drag having ended, continues
/// the one without drag. stop_at_step stops the first of the two runs that
/// still takes that step (each counts its own steps from t = 0).
nlohmann::json runCase(const Model& model, const RunOptions& options);

} // namespace lamina::membrane
