// The `membrane` program: thin CLI over lamina::membrane (run, converge).
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "membrane/converge.hpp"
#include "membrane/io/case_file.hpp"
#include "membrane/io/checkpoint.hpp"
#include "membrane/loads/blast.hpp"
#include "membrane/run.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
  using namespace lamina;
  CLI::App app{
      "lamina membrane solver (linear or large-deflection triangles, Newmark or explicit)"};
  app.require_subcommand(1);
  std::string case_path, out_dir, library;
  std::vector<std::string> overrides;
  bool json = false;
  int levels = 3, sample_every = 1;

  // The options both commands share: the case file, the library, --set, --json.
  auto addCaseOptions = [&](CLI::App* cmd, const std::string& case_help,
                            const std::string& json_help) {
    cmd->add_option("case", case_path, case_help)->required();
    cmd->add_flag("--json", json, json_help);
    cmd->add_option("--library", library, "materials library file");
    cmd->add_option("--set", overrides, "override a case key: --set time.dt=1e-7 (repeatable)")
        ->allow_extra_args(false); // one value per flag, so a positional may follow
  };

  auto* run = app.add_subcommand("run", "run one case file");
  addCaseOptions(run, "case file (TOML)", "print summary.json on stdout");
  run->add_option("--out", out_dir, "output folder (default: out/<case file stem>)");
  std::string restart_dir;
  long stop_at_step = 0;
  run->add_option("--restart", restart_dir,
                  "continue the run whose outputs are in DIR from DIR/checkpoint.h5 "
                  "(same case file and --set options)");
  run->add_option("--stop-at-step", stop_at_step,
                  "stop after step N with a checkpoint (continue later with --restart)")
      ->check(CLI::PositiveNumber);

  auto* conv = app.add_subcommand("converge", "convergence study (paper section 4)");
  addCaseOptions(conv, "case file (TOML, structured mesh)", "print the rates as JSON");
  conv->add_option("--levels", levels, "number of grids (>= 3)")->required();
  conv->add_option("--sample-every", sample_every, "compare every n-th coarse step");

  auto* blast = app.add_subcommand("blast", "Kingery-Bulmash blast parameters at one distance");
  double charge = 0, distance = 0, tnt_factor = 1.0;
  std::string burst_name = "hemispherical";
  blast->add_option("--charge", charge, "explosive mass W, kg")->required();
  blast->add_option("--distance", distance, "distance from the charge centre R, m")->required();
  blast->add_option("--burst", burst_name, "hemispherical (surface) or spherical (free air)")
      ->check(CLI::IsMember({"hemispherical", "spherical"}));
  blast->add_option("--tnt-factor", tnt_factor, "TNT-equivalence factor (W_TNT = factor * W)");
  blast->add_flag("--json", json, "print the parameters as JSON (SI units)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  try {
    if (blast->parsed()) {
      const auto burst = membrane::parseBurst(burst_name);
      LAMINA_CHECK(std::isfinite(tnt_factor) && tnt_factor > 0,
                   "--tnt-factor must be positive, got ", tnt_factor);
      const auto p = membrane::kingeryBulmash(charge * tnt_factor, distance, burst);
      if (json)
        std::cout << membrane::blastToJson(p, burst).dump(2) << "\n";
      else
        std::cout << membrane::blastTable(p, burst);
      return kExitOk;
    }
    membrane::MaterialSources sources{library, ""};
    const bool quiet = json; // ProgressLine itself logs sparsely when stderr is not a tty
    if (run->parsed()) {
      const core::InterruptGuard interrupts; // SIGINT/SIGTERM end the run cleanly
      const auto model = membrane::readCase(case_path, overrides, sources);
      membrane::RunOptions opt;
      if (!restart_dir.empty()) { // a restart continues in the folder of the run
        if (!out_dir.empty() && std::filesystem::weakly_canonical(out_dir) !=
                                    std::filesystem::weakly_canonical(restart_dir))
          throw Error("--out and --restart name different folders; a restart continues in the "
                      "folder of the interrupted run",
                      {"", 0, "--out"});
        out_dir = restart_dir;
      }
      if (out_dir.empty()) // never litter the working directory
        out_dir = (std::filesystem::path("out") / std::filesystem::path(case_path).stem()).string();
      // the output folder is a folder (or new), and not an input of the run
      std::error_code ec;
      if (std::filesystem::exists(out_dir, ec) && !std::filesystem::is_directory(out_dir, ec))
        throw Error("the output folder exists and is not a directory; refusing to replace it",
                    {out_dir, 0, "--out"});
      core::checkOutputIsNotInput(out_dir, {case_path, library}, "--out");
      opt.out_dir = out_dir;
      opt.quiet = quiet;
      opt.restart = !restart_dir.empty();
      opt.stop_at_step = stop_at_step;
      opt.case_digest = membrane::caseDigest(case_path, overrides);
      const auto summary = membrane::runCase(model, opt);
      if (json)
        std::cout << summary.dump(2) << "\n";
      else
        std::cerr << "membrane: " << model.name << ": " << summary["steps"] << " steps, max |w| "
                  << summary["max_abs_w"] << " m, energy balance "
                  << summary["energy"]["max_abs_balance"] << " J; results in " << out_dir << "\n";
    } else {
      const auto study =
          membrane::runConvergence(case_path, overrides, sources, levels, sample_every, quiet);
      if (json)
        std::cout << study.toJson().dump(2) << "\n";
      else
        std::cout << study.toTable();
    }
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
