// The `membrane` program: thin CLI over lamina::membrane (run, converge, blast).
#include "core/atomic_file.hpp"
#include "core/command_line.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/interrupt.hpp"
#include "core/parallel.hpp"
#include "core/resources.hpp"
#include "membrane/converge.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/io/checkpoint.hpp"
#include "membrane/loads/blast.hpp"
#include "membrane/run.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

namespace {

using namespace lamina;

/// Every option of the command line (each subcommand reads its own).
struct Options {
  std::string case_path, out_dir;
  core::SharedOptions shared; ///< --library, --catalog, --set, --threads, --json, --quiet
  // run
  std::string restart_dir;
  long stop_at_step = 0;
  // converge
  int levels = 3, sample_every = 1;
  // blast
  double charge = 0, distance = 0, tnt_factor = 1.0;
  std::string burst_name = "hemispherical";
};

/// The case file of run and converge.
void addCaseArgument(CLI::App* cmd, Options& o, const std::string& case_help) {
  cmd->add_option("case", o.case_path, case_help)->required();
}

/// The shared options of run and converge (core/command_line.hpp).
constexpr core::Shared kCaseOptions = core::Shared::Library | core::Shared::Catalog |
                                      core::Shared::Set | core::Shared::Threads |
                                      core::Shared::Json | core::Shared::Quiet;

CLI::App* addRunCommand(CLI::App& app, Options& o) {
  auto* run = app.add_subcommand("run", "run one case file");
  addCaseArgument(run, o, "case file (TOML); --json prints its summary.json");
  run->add_option("--out", o.out_dir, "output folder (default: out/<case file stem>)")
      ->default_str("");
  run->add_option("--restart", o.restart_dir,
                  "continue the run whose outputs are in DIR from DIR/checkpoint.h5 "
                  "(same case file and --set options)");
  run->add_option("--stop-at-step", o.stop_at_step,
                  "stop after step N with a checkpoint (continue later with --restart)")
      ->check(CLI::PositiveNumber)
      ->default_str("");
  return run;
}

CLI::App* addConvergeCommand(CLI::App& app, Options& o) {
  auto* conv = app.add_subcommand("converge", "convergence study (paper section 4)");
  addCaseArgument(conv, o, "case file (TOML, structured mesh); --json prints the rates");
  conv->add_option("--levels", o.levels, "number of grids (>= 3)")->required()->default_str("");
  conv->add_option("--sample-every", o.sample_every, "compare every n-th coarse step");
  return conv;
}

CLI::App* addBlastCommand(CLI::App& app, Options& o) {
  auto* blast = app.add_subcommand("blast", "Kingery-Bulmash blast parameters at one distance");
  blast->add_option("--charge", o.charge, "explosive mass W, kg")->required()->default_str("");
  blast->add_option("--distance", o.distance, "distance from the charge centre R, m")
      ->required()
      ->default_str("");
  blast->add_option("--burst", o.burst_name, "hemispherical (surface) or spherical (free air)")
      ->check(CLI::IsMember(membrane::kBurstNames.names()));
  blast->add_option("--tnt-factor", o.tnt_factor, "TNT-equivalence factor (W_TNT = factor * W)");
  // --json prints the parameters in SI units
  return blast;
}

/// `membrane blast`: prints the blast parameters.
void blastCommand(const Options& o) {
  const auto burst = membrane::parseBurst(o.burst_name);
  LAMINA_CHECK(std::isfinite(o.tnt_factor) && o.tnt_factor > 0,
               "--tnt-factor must be positive, got ", o.tnt_factor);
  const auto p = membrane::kingeryBulmash(o.charge * o.tnt_factor, o.distance, burst);
  if (o.shared.json)
    std::cout << membrane::blastToJson(p, burst).dump(2) << "\n";
  else
    std::cout << membrane::blastTable(p, burst);
}

/// The folder a run writes to: --restart's (a restart continues in the
/// folder of the run), else --out, else out/<case file stem>; refused when
/// it is not a folder or names one of the run's inputs.
std::string outputFolder(const Options& o) {
  std::string out_dir = o.out_dir;
  if (!o.restart_dir.empty()) {
    if (!out_dir.empty() && std::filesystem::weakly_canonical(out_dir) !=
                                std::filesystem::weakly_canonical(o.restart_dir))
      throw Error("--out and --restart name different folders; a restart continues in the "
                  "folder of the interrupted run",
                  {"", 0, "--out"});
    out_dir = o.restart_dir;
  }
  if (out_dir.empty()) // never litter the working directory
    out_dir = (std::filesystem::path("out") / std::filesystem::path(o.case_path).stem()).string();
  // the output folder is a folder (or new), and not an input of the run
  std::error_code ec;
  if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
    throw Error("the output folder exists and is not a directory; refusing to replace it",
                {out_dir, 0, "--out"});
  core::checkOutputIsNotInput(out_dir, {o.case_path, o.shared.library, o.shared.catalog}, "--out");
  return out_dir;
}

/// `membrane run`: runs the case, prints its summary.
void runCommand(const Options& o) {
  const core::InterruptGuard interrupts; // SIGINT/SIGTERM end the run cleanly
  const membrane::MaterialSources sources{o.shared.library, o.shared.catalog};
  const auto model = membrane::readCase(o.case_path, o.shared.overrides, sources);
  const std::string out_dir = outputFolder(o);
  membrane::RunOptions opt;
  opt.out_dir = out_dir;
  opt.quiet = o.shared.json || o.shared.quiet; // ProgressLine logs sparsely when not a tty
  opt.restart = !o.restart_dir.empty();
  opt.stop_at_step = o.stop_at_step;
  opt.case_digest = membrane::caseDigest(o.case_path, o.shared.overrides);
  const auto summary = membrane::runCase(model, opt);
  if (o.shared.json)
    std::cout << summary.dump(2) << "\n";
  else
    std::cerr << "membrane: " << model.name << ": " << summary["steps"] << " steps, max |w| "
              << core::formatShort(summary["max_abs_w"].get<double>()) << " m, energy balance "
              << core::formatShort(summary["energy"]["max_abs_balance"].get<double>())
              << " J; results in " << out_dir << "\n";
}

/// `membrane converge`: runs the convergence study, prints its rates.
void convergeCommand(const Options& o) {
  const membrane::MaterialSources sources{o.shared.library, o.shared.catalog};
  const auto study =
      membrane::runConvergence(o.case_path, o.shared.overrides, sources, o.levels, o.sample_every,
                               /*quiet=*/o.shared.json || o.shared.quiet);
  if (o.shared.json)
    std::cout << study.toJson().dump(2) << "\n";
  else
    std::cout << study.toTable();
}

/// Runs @p command; an error becomes one line on stderr and the exit code
/// of its kind (core/error.hpp).
template <class Command>
int reportErrors(Command&& command) {
  try {
    command();
  } catch (const Interrupted& e) {
    std::cerr << "membrane: " << e.what() << "\n";
    return e.exitCode();
  } catch (const DivergenceError& e) {
    std::cerr << "membrane: diverged: " << e.what() << "\n";
    return kExitDivergence;
  } catch (const Error& e) {
    std::cerr << "membrane: error: " << e.what() << "\n";
    return kExitUserError;
  } catch (const std::exception& e) {
    std::cerr << "membrane: error: " << e.what() << "\n";
    return kExitUserError;
  } catch (...) {
    std::cerr << "membrane: error: unexpected error (not a std::exception)\n";
    return kExitUserError;
  }
  return kExitOk;
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "lamina membrane solver (linear or large-deflection triangles, Newmark or explicit)"};
  core::showDefaults(app);
  Options o;
  CLI::App* run = addRunCommand(app, o);
  CLI::App* converge = addConvergeCommand(app, o);
  CLI::App* blast = addBlastCommand(app, o);
  core::addSharedOptions(app, o.shared,
                         {{run, kCaseOptions}, {converge, kCaseOptions}, {blast, core::Shared::Json}});
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return core::reportUsageError(app, e, "membrane");
  }
  return reportErrors([&] {
    core::checkThreads(o.shared.threads, "--threads");
    std::optional<core::ThreadsScope> threads;
    if (o.shared.threads > 0)
      threads.emplace(o.shared.threads);
    if (blast->parsed())
      blastCommand(o);
    else if (run->parsed())
      runCommand(o);
    else
      convergeCommand(o);
  });
}
