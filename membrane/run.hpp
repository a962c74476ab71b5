#pragma once
/// @file run.hpp
/// @brief `membrane run`: set up, step, write the outputs of one case.
///
/// Writes into the output folder: <name>.xdmf + <name>.h5 (fields),
/// probes.csv (t,<probe>_ux,_uy,_uz,_vx,_vy,_vz,...), energy.csv,
/// reactions.csv (per constraint set, when there are constraints) and
/// summary.json (written atomically last). On divergence the last finite
/// state is written, summary.json records the message and
/// lamina::DivergenceError is rethrown (exit code 3).

#include "membrane/model/model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace lamina::membrane {

/// Options of one run.
struct RunOptions {
  std::filesystem::path out_dir = "."; ///< output folder (created)
  bool quiet = false;                  ///< no progress line
};

/// Runs @p model and @return the summary object (also written to summary.json).
nlohmann::json runModel(const Model& model, const RunOptions& options);

/// `membrane run`: runModel, or for `compare_without_drag = true` two runs
/// (DIR/with-drag, DIR/without-drag) and DIR/summary.json = the with-drag
/// summary plus "drag_comparison" {with_drag, without_drag: {max_abs_w,
/// peak_reaction (largest per-set peak), peak_total_reaction (peak of the
/// magnitude of the sum of all reactions, springs included), max_speed}}.
nlohmann::json runCase(const Model& model, const RunOptions& options);

} // namespace lamina::membrane
