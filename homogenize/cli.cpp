/// @file cli.cpp
/// @brief `homogenize CELL.toml --name NAME [--library PATH] [--json]
/// [--threads N] [--tol T] [--resolution N] [--set KEY=VALUE]`: effective C and density of a
/// unit cell into the materials library. With `--path P --rate R --to S`:
/// the nonlinear cell under that strain-rate history (nonlinear_run.hpp).
/// With `--reduced-order [--partitions K] [--partition-seed S]`: the cell's
/// reduced-order model as one library entry (reduced_order_run.hpp).
/// Under `mpirun -np N` the linear homogenization runs over N ranks (rank 0
/// builds the cell, scatters it, prints and writes the library).

#include "homogenize/cli.hpp"

#include "core/atomic_file.hpp"
#include "core/command_line.hpp"
#include "core/enum_names.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/resources.hpp"
#include "homogenize/distribution.hpp"
#include "homogenize/homogenizer.hpp"
#include "homogenize/library_entry.hpp"
#include "homogenize/memory_estimate.hpp"
#include "homogenize/nonlinear_run.hpp"
#include "homogenize/reduced_order_run.hpp"
#include "materials/catalog.hpp"
#include "materials/library.hpp"
#include "materials/point_driver.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace {

using lamina::core::formatShort;

void printDispersion(const lamina::homogenize::EntryResult& e) {
  if (!e.dispersion) {
    std::printf("no micro-inertia: the cell has no size in metres ([cell] size)\n");
    return;
  }
  const auto& d = *e.dispersion;
  std::printf("dispersion zeta^2 D_lin (kg/m, lamina order; eqs. 38-39):\n");
  std::printf("%s", lamina::core::formatMatrix6(d.D, 1.0, 5, 12, "  ").c_str());
  std::string line = "eq. 39 least-squares residual per load case";
  for (double r : d.residual)
    line += " " + formatShort(r, 2);
  line += "\ncharacteristic length sqrt(zeta^2 D_II / rho) (m):";
  for (int i = 0; i < 6; ++i)
    line += " " + formatShort(std::sqrt(std::max(0.0, d.D(i, i)) / e.result.density), 3);
  std::printf("%s\n", line.c_str());
}

void printHuman(const lamina::homogenize::EntryResult& e, const lamina::micro::UnitCell& cell,
                const std::string& library) {
  const std::string& name = e.name;
  const lamina::homogenize::Result& r = e.result;
  std::printf("%s: %zu voxels (%d x %d x %d), density %s kg/m^3\n", name.c_str(), r.voxels,
              cell.n[0], cell.n[1], cell.n[2], formatShort(r.density).c_str());
  std::printf("C (GPa, lamina order xx yy zz xy yz xz, engineering shear):\n");
  std::printf("%s", lamina::core::formatMatrix6(r.C, 1e-9, 6, 12, "  ").c_str());
  std::string line = "load cases: CG iterations";
  for (int it : r.iterations())
    line += " " + std::to_string(it);
  line += ", final residuals";
  for (const auto& c : r.cases)
    line += " " + formatShort(c.residual, 2);
  std::printf("%s\n", line.c_str());
  std::printf("asymmetry before symmetrizing %s, symmetry %s (tol %s), wall %s s\n",
              formatShort(r.asymmetry, 3).c_str(),
              lamina::materials::toString(r.symmetry.cls).c_str(),
              formatShort(r.symmetry_tol, 1).c_str(), formatShort(r.wall_s, 3).c_str());
  printDispersion(e);
  std::printf("added '%s' to %s\n", name.c_str(), library.c_str());
}

/// --fftw-plan: FFTW planning.
enum class FftwPlan { Auto, Estimate, Measure };
constexpr auto kPlans = lamina::core::enumNames<FftwPlan>(
    {{"auto", FftwPlan::Auto}, {"estimate", FftwPlan::Estimate}, {"measure", FftwPlan::Measure}});

/// --precision: precision of the preconditioner's FFTs (Auto: from --tol);
/// single also makes the operator and the CG vectors float from --tol 1e-4
/// up (homogenize::floatVectors).
enum class PrecisionChoice { Auto, Single, Double };
constexpr auto kPrecisions =
    lamina::core::enumNames<PrecisionChoice>({{"auto", PrecisionChoice::Auto},
                                              {"single", PrecisionChoice::Single},
                                              {"double", PrecisionChoice::Double}});

/// --estimate: how C is formed from the six solutions.
constexpr auto kEstimates = lamina::core::enumNames<lamina::homogenize::Estimate>(
    {{"energy", lamina::homogenize::Estimate::Energy},
     {"stress", lamina::homogenize::Estimate::Stress}});

/// @return the `measure` of homogenize::Options: 1 yes, 0 no, -1 auto
int measureFlag(FftwPlan plan) {
  return plan == FftwPlan::Auto ? -1 : plan == FftwPlan::Measure ? 1 : 0;
}

/// The command line, parsed: the choices as enums.
struct Cli {
  std::string cell_path, name, out;
  lamina::core::SharedOptions shared; ///< --library, --catalog, --set, --threads, --json, --quiet
  bool overwrite = false;
  int resolution = 0;
  double tol = 1e-5, eta = 0.1;
  FftwPlan plan = FftwPlan::Auto;
  lamina::homogenize::Estimate estimate = lamina::homogenize::Estimate::Energy;
  PrecisionChoice precision = PrecisionChoice::Auto;
  bool path_given = false; ///< --path was on the command line
  lamina::homogenize::PathSpec path;
  lamina::homogenize::TangentSpec tangent;
  std::vector<int> field_steps;
  bool reduced_order = false; ///< --reduced-order: a reduced-order cell entry
  int partitions = 0;         ///< --partitions K per phase (0: not given, one per phase)
  std::int64_t partition_seed =
      static_cast<std::int64_t>(lamina::homogenize::kDefaultPartitionSeed);

  /// @return true for a nonlinear run (a strain path or rate-dependent tangents)
  bool nonlinear() const { return path_given || !tangent.rates.empty(); }
};

/// The strings CLI11 fills in; turned into the enums of Cli once, after parsing.
struct CliNames {
  std::string plan = "auto", estimate = "energy", precision = "auto", path;
  std::string scheme = "tfa";           ///< --scheme of --reduced-order
  CLI::Option* scheme_option = nullptr; ///< --scheme, to tell whether it was given
  CLI::Option* rate = nullptr;          ///< --rate, to tell whether it was given
  CLI::Option* to = nullptr;            ///< --to, likewise
  CLI::Option* tol = nullptr;           ///< --tol (the reduced-order default is tighter)
  CLI::Option* seed = nullptr;          ///< --partition-seed
};

void addReducedOrderOptions(CLI::App& app, Cli& cli, CliNames& names);

/// Declares every option of the program on @p app, into @p cli and @p names.
void addOptions(CLI::App& app, Cli& cli, CliNames& names) {
  lamina::core::showDefaults(app);
  app.add_option("cell", cli.cell_path, "cell file (TOML)")->required();
  app.add_option("--name", cli.name,
                 "library entry name; required to add entries (linear, --tangent-rates, "
                 "--reduced-order), not for a --path run alone (with a J sweep: NAME-J<J>; "
                 "with --tangent-rates: NAME-R<rate>)");
  using lamina::core::Shared;
  lamina::core::addSharedOptions(app, cli.shared,
                                 Shared::Library | Shared::Catalog | Shared::Set | Shared::Threads |
                                     Shared::Json | Shared::Quiet);
  names.tol = app.add_option("--tol", cli.tol,
                             "relative residual per load case (with --reduced-order the "
                             "default is 1e-8)")
                  ->check(CLI::PositiveNumber);
  app.add_option("--resolution", cli.resolution,
                 "override the cell's resolution: N^3 voxels (default: the cell's)")
      ->check(CLI::Range(2, 4096))
      ->default_str("");
  app.add_flag("--overwrite", cli.overwrite, "replace an existing entry of the same name");
  app.add_option("--fftw-plan", names.plan,
                 "FFTW planning: estimate, measure (wisdom cached in ~/.cache/lamina), "
                 "auto (measure above 64^3)")
      ->check(CLI::IsMember(kPlans.names()));
  app.add_option("--estimate", names.estimate,
                 "C from the six solutions: energy (<eps_j:C:eps_k>, error quadratic in the "
                 "residual, keeps 6 displacement fields) or stress (<sigma_k>, least memory)")
      ->check(CLI::IsMember(kEstimates.names()));
  app.add_option("--precision", names.precision,
                 "precision of the FFTs: auto (single when tol >= 1e-6), single, double; in "
                 "single from tol 1e-4 up the operator and the CG vectors are float too")
      ->check(CLI::IsMember(kPrecisions.names()));
  // nonlinear: the cell under a strain-rate history (docs/homogenize-nonlinear.md)
  app.add_option("--path", names.path,
                 "nonlinear run along this strain path (one of the names listed; with "
                 "--out, --rate and --to are required; with --tangent-rates: the path to "
                 "--tangent-strain)")
      ->check(CLI::IsMember(lamina::materials::kDrivePathNames.names()));
  names.rate = app.add_option("--rate", cli.path.rate,
                              "nonlinear: driven strain rate (1/s, 1e-12 to 1e12; required "
                              "with --path ... --out)") // range: materials::checkRate
                   ->default_str("");
  names.to = app.add_option("--to", cli.path.to,
                            "nonlinear: final driven strain (required with --path ... --out; "
                            "confined: below 1)")
                 ->check(CLI::PositiveNumber)
                 ->default_str("");
  app.add_option("--steps", cli.path.steps, "nonlinear: load steps per leg")
      ->check(CLI::Range(1, 10000000));
  app.add_flag("--unload", cli.path.unload, "nonlinear: back to zero strain at the same rate");
  app.add_option("--out", cli.out, "nonlinear: history CSV (also OUT-phases.csv, OUT-fields.h5)");
  app.add_option("--fields", cli.field_steps, "nonlinear: steps whose fields are written (XDMF)")
      ->delimiter(',')
      ->default_str("");
  app.add_option("--eta", cli.eta, "nonlinear: CG forcing term per Newton step")
      ->check(CLI::Range(1e-12, 0.9));
  app.add_option("--tangent-rates", cli.tangent.rates,
                 "rates (1/s, 1e-12 to 1e12, inf allowed) of effective tangent entries "
                 "NAME-R<rate>, added all or none")
      ->delimiter(',')
      ->default_str("");
  app.add_option("--tangent-strain", cli.tangent.strain,
                 "driven strain of the state of the tangent entries")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--tangent-increment", cli.tangent.increment,
                 "strain increment a tangent is for, in (0, 1]: dt = increment / rate")
      ->check(CLI::PositiveNumber);
  addReducedOrderOptions(app, cli, names);
}

/// Declares the options of a reduced-order cell (docs/homogenize-nonlinear.md,
/// "Reduced-order cells") on @p app.
void addReducedOrderOptions(CLI::App& app, Cli& cli, CliNames& names) {
  app.add_flag("--reduced-order", cli.reduced_order,
               "add the cell's reduced-order model (influence functions of its partitions) as "
               "one library entry NAME");
  app.add_option("--partitions", cli.partitions,
                 "reduced-order: K partitions per phase by k-means of the voxels' strain "
                 "concentration tensors (default: one partition per phase)")
      ->check(CLI::Range(1, 1 << 20))
      ->default_str("");
  names.seed = app.add_option("--partition-seed", cli.partition_seed,
                              "reduced-order: seed of the k-means++ seeding")
                   ->check(CLI::NonNegativeNumber);
  names.scheme_option =
      app.add_option("--scheme", names.scheme,
                     "reduced-order: how the partitions interact, tfa (transformation-field "
                     "analysis, the chapter's eqs. 22-34) or clustering (clustering analysis in a "
                     "reference medium that follows the softest "
                     "phase as it flows)")
          ->check(CLI::IsMember(lamina::materials::kReducedOrderSchemeNames.names()));
}

/// @return the value of @p name in @p choices (a core::EnumNames; @p name
/// was checked by CLI::IsMember against its names())
template <class Choices>
auto valueOf(const Choices& choices, const std::string& name) {
  const auto value = choices.parse(name);
  LAMINA_CHECK(value, "'", name, "' is not a choice of the command line");
  return *value;
}

/// Turns the checked strings of @p names into the enums of @p cli.
void parseChoices(const CliNames& names, Cli& cli) {
  cli.plan = valueOf(kPlans, names.plan);
  cli.estimate = valueOf(kEstimates, names.estimate);
  cli.precision = valueOf(kPrecisions, names.precision);
  cli.path_given = !names.path.empty();
  if (cli.path_given)
    cli.path.path = valueOf(lamina::materials::kDrivePathNames, names.path);
}

/// The one rule of a strain path (as `materials drive`): a --path run
/// (--out) needs --rate and --to; without one they would be ignored, so
/// they are refused. Throws a CLI error (exit 2) naming the option.
void checkPathOptions(const Cli& cli, const CliNames& names) {
  const bool path_run = cli.path_given && !cli.out.empty();
  if (path_run && names.rate->count() == 0)
    throw CLI::RequiredError("--rate: a --path run needs --rate R (driven strain rate, 1/s)",
                             CLI::ExitCodes::RequiredError);
  if (path_run && names.to->count() == 0)
    throw CLI::RequiredError("--to: a --path run needs --to S (final driven strain)",
                             CLI::ExitCodes::RequiredError);
  if (cli.path_given && cli.out.empty() && cli.tangent.rates.empty())
    throw CLI::RequiredError("--out: a --path run needs --out FILE.csv (or --tangent-rates)",
                             CLI::ExitCodes::RequiredError);
  for (const CLI::Option* o : {names.rate, names.to}) {
    if (o->count() == 0 || path_run)
      continue;
    throw CLI::ValidationError(
        o->get_name() + (cli.path_given ? ": drives a --path run (with --out) only; tangent "
                                          "entries take --tangent-rates and --tangent-strain"
                                        : ": only with --path (a strain path run)"),
        CLI::ExitCodes::ValidationError);
  }
}

/// The rules of --reduced-order: one mode at a time (not with a strain path
/// or tangent entries), --partitions and --partition-seed only with it (the
/// seed only with --partitions). Throws a CLI error (exit 2) naming the options.
void checkReducedOrderOptions(const Cli& cli, const CliNames& names) {
  if (cli.reduced_order && (cli.path_given || !cli.tangent.rates.empty()))
    throw CLI::ValidationError(std::string("--reduced-order and ") +
                                   (cli.path_given ? "--path" : "--tangent-rates") +
                                   ": a reduced-order cell entry is a mode of its own (run "
                                   "them as two commands)",
                               CLI::ExitCodes::ValidationError);
  if (!cli.reduced_order &&
      (cli.partitions > 0 || names.seed->count() > 0 || names.scheme_option->count() > 0))
    throw CLI::ValidationError(std::string(cli.partitions > 0        ? "--partitions"
                                           : names.seed->count() > 0 ? "--partition-seed"
                                                                     : "--scheme") +
                                   ": only with --reduced-order",
                               CLI::ExitCodes::ValidationError);
  if (names.seed->count() > 0 && cli.partitions == 0)
    throw CLI::ValidationError("--partition-seed: seeds the k-means of --partitions K (without "
                               "it every phase is one partition)",
                               CLI::ExitCodes::ValidationError);
}

/// The build options of --reduced-order.
lamina::homogenize::ReducedOrderOptions reducedOrderOptions(const Cli& cli, const CliNames& names) {
  lamina::homogenize::ReducedOrderOptions opt;
  if (names.tol->count() > 0)
    opt.tol = cli.tol;
  opt.threads = cli.shared.threads;
  opt.measure = measureFlag(cli.plan);
  opt.quiet = cli.shared.quiet || cli.shared.json;
  if (cli.partitions > 0) {
    opt.partitions.method = lamina::homogenize::PartitionMethod::KMeans;
    opt.partitions.per_phase = cli.partitions;
    opt.partitions.seed = static_cast<std::uint64_t>(cli.partition_seed);
  }
  opt.scheme = valueOf(lamina::materials::kReducedOrderSchemeNames, names.scheme);
  return opt;
}

/// Checks --reduced-order against @p spec and the library before the cell
/// is built: a name that is free, a serial run, the memory of the build.
void checkReducedOrder(const Cli& cli, const lamina::micro::CellSpec& spec,
                       const std::array<int, 3>& n, const lamina::homogenize::MpiSession& mpi) {
  using namespace lamina;
  if (cli.name.empty())
    throw Error("--reduced-order needs --name NAME", {"", 0, "--name"});
  LAMINA_CHECK(mpi.ranks() == 1, "reduced-order builds are serial (no mpirun)");
  const materials::Library lib(materials::Library::resolvePath(cli.shared.library));
  lib.checkNewNames({cli.name}, cli.overwrite, "--name");
  const std::size_t voxels = static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
                             static_cast<std::size_t>(n[2]);
  const int partitions = std::max(1, cli.partitions) * static_cast<int>(spec.phases.size());
  core::requireMemory(
      homogenize::ReducedOrderBuilder::memoryBytes(voxels, partitions, spec.physical_size),
      "a reduced-order build of " + std::to_string(voxels) + " voxels into up to " +
          std::to_string(partitions) + " partitions",
      {cli.cell_path, 0, cli.resolution > 0 ? "--resolution" : "cell.resolution"},
      "use fewer voxels (--resolution) or fewer partitions (--partitions)");
}

/// Checks the nonlinear arguments against @p spec before the cell is built:
/// the rate and strain ranges, the tangent entry names, and that no output
/// file replaces a non-regular file or an input of the run.
void checkNonlinear(const Cli& cli, const lamina::micro::CellSpec& spec) {
  using namespace lamina;
  if (cli.path_given && !cli.out.empty()) {
    materials::checkRate(cli.path.rate, "--rate");
    materials::checkFinalStrain(cli.path.path, cli.path.to, "--to");
    std::vector<std::filesystem::path> inputs{
        cli.cell_path, materials::Library::resolvePath(cli.shared.library),
        cli.shared.catalog.empty() ? materials::Catalog::defaultPath()
                                   : std::filesystem::path(cli.shared.catalog)};
    if (spec.image)
      inputs.push_back(spec.image->path);
    for (const auto& f : homogenize::pathOutputs(cli.out, !cli.field_steps.empty()))
      core::checkOutput(f, inputs, "--out");
  }
  if (!cli.tangent.rates.empty()) {
    if (cli.name.empty())
      throw Error("--tangent-rates needs --name NAME", {"", 0, "--name"});
    homogenize::TangentSpec tangent = cli.tangent;
    tangent.path = cli.path;
    const materials::Library lib(materials::Library::resolvePath(cli.shared.library));
    homogenize::checkTangentSpec(cli.name, tangent, lib, cli.overwrite);
  }
}

/// The solver settings of the linear homogenization from the command line.
lamina::homogenize::Options linearOptions(const Cli& cli, bool quiet) {
  namespace hom = lamina::homogenize;
  hom::Options opt;
  opt.tol = cli.tol;
  opt.threads = cli.shared.threads;
  opt.measure = measureFlag(cli.plan);
  opt.quiet = quiet;
  opt.estimate = cli.estimate;
  if (cli.precision != PrecisionChoice::Auto)
    opt.precision =
        cli.precision == PrecisionChoice::Single ? hom::Precision::Single : hom::Precision::Double;
  return opt;
}

/// Refuses, before anything large is allocated, a grid of @p n voxels that
/// does not fit in memory (docs/homogenize-solver.md, Memory).
void checkMemory(const Cli& cli, const lamina::micro::CellSpec& spec, const std::array<int, 3>& n,
                 const lamina::homogenize::MpiSession& mpi) {
  const std::uint64_t voxels = static_cast<std::uint64_t>(n[0]) * static_cast<std::uint64_t>(n[1]) *
                               static_cast<std::uint64_t>(n[2]);
  lamina::core::requireMemory(
      lamina::homogenize::linearSolveBytes(voxels, linearOptions(cli, true), spec.physical_size,
                                           mpi.ranks(), mpi.rank()),
      "homogenizing " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
          std::to_string(n[2]) + " voxels",
      {cli.cell_path, 0, cli.resolution > 0 ? "--resolution" : "cell.resolution"},
      "run it distributed: mpirun -np N homogenize " + cli.cell_path +
          " ... (each rank holds 1/N of the fields), or --estimate stress "
          "--precision single with --tol 1e-4 or looser (52 bytes per voxel)");
}

/// Rank 0 builds the phase map of @p spec at @p n voxels; the others learn only its grid.
lamina::micro::UnitCell buildCell(const lamina::micro::CellSpec& spec, const std::array<int, 3>& n,
                                  lamina::homogenize::MpiSession& mpi) {
  lamina::micro::UnitCell cell;
  if (mpi.rank() == 0)
    cell = lamina::micro::buildCell(spec, n);
  double shape[6] = {static_cast<double>(cell.n[0]),
                     static_cast<double>(cell.n[1]),
                     static_cast<double>(cell.n[2]),
                     cell.size[0],
                     cell.size[1],
                     cell.size[2]};
  mpi.broadcast(shape, sizeof shape);
  for (int d = 0; d < 3; ++d) {
    cell.n[static_cast<std::size_t>(d)] = static_cast<int>(shape[d]);
    cell.size[d] = shape[3 + d];
  }
  return cell;
}

/// The nonlinear cell along --path with its history in --out (serial).
void runPath(const Cli& cli, const lamina::micro::CellSpec& spec,
             const lamina::micro::UnitCell& cell, const lamina::homogenize::NonlinearOptions& nl) {
  using namespace lamina;
  const auto t0 = std::chrono::steady_clock::now();
  const auto steps = homogenize::runPath(
      spec, cell, cli.path, nl, cli.out, cli.field_steps, [&](const homogenize::StepResult& r) {
        if (!cli.shared.quiet)
          std::fprintf(stderr,
                       "step %d t %.4g s: E %.4g %.4g %.4g %.4g %.4g %.4g, Sigma %.4g %.4g "
                       "%.4g %.4g %.4g %.4g MPa, newton %d krylov %d (%.2f s)\n",
                       r.step, r.t, r.E[0], r.E[1], r.E[2], r.E[3], r.E[4], r.E[5],
                       r.Sigma[0] / 1e6, r.Sigma[1] / 1e6, r.Sigma[2] / 1e6, r.Sigma[3] / 1e6,
                       r.Sigma[4] / 1e6, r.Sigma[5] / 1e6, r.newton, r.krylov, r.wall_s);
      });
  int newton = 0, krylov = 0;
  for (const auto& r : steps) {
    newton += r.newton;
    krylov += r.krylov;
  }
  std::printf("%zu steps of %s at %g /s on %d x %d x %d voxels: newton %d, krylov %d, "
              "wall %.2f s; wrote %s\n",
              steps.size(), materials::toString(cli.path.path), cli.path.rate, cell.n[0], cell.n[1],
              cell.n[2], newton, krylov,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              cli.out.c_str());
}

/// The nonlinear run: the strain path (--path, --out) and/or the
/// rate-dependent tangent entries (--tangent-rates) into the library.
void runNonlinear(const Cli& cli, const lamina::micro::CellSpec& spec,
                  const lamina::micro::UnitCell& cell, const lamina::homogenize::MpiSession& mpi) {
  using namespace lamina;
  LAMINA_CHECK(mpi.ranks() == 1, "nonlinear runs are serial (no mpirun)");
  homogenize::NonlinearOptions nl;
  nl.tol = cli.tol;
  nl.eta = cli.eta;
  nl.threads = cli.shared.threads;
  nl.measure = measureFlag(cli.plan);
  if (cli.path_given && !cli.out.empty())
    runPath(cli, spec, cell, nl);
  else if (cli.path_given && cli.tangent.rates.empty())
    throw Error("a nonlinear run needs --out FILE.csv (or --tangent-rates)");
  if (cli.tangent.rates.empty())
    return;
  if (cli.name.empty())
    throw Error("--tangent-rates needs --name NAME");
  homogenize::TangentSpec tangent = cli.tangent;
  tangent.path = cli.path;
  materials::Library lib(materials::Library::resolvePath(cli.shared.library));
  homogenize::addTangentEntries(
      spec, cell, cli.name, tangent, nl, lib, cli.overwrite, [&](const materials::Material& m) {
        if (cli.shared.json) // one JSON line per entry, as the linear run's
          std::cout << nlohmann::json{{"name", m.name}, {"library", lib.path().string()}}.dump()
                    << std::endl;
        else
          std::printf("added '%s' to %s\n", m.name.c_str(), lib.path().string().c_str());
      });
}

/// The reduced-order cell into the library (serial), with its summary.
void runReducedOrder(const Cli& cli, const CliNames& names, const lamina::micro::CellSpec& spec,
                     const lamina::micro::UnitCell& cell) {
  using namespace lamina;
  materials::Library lib(materials::Library::resolvePath(cli.shared.library));
  const homogenize::ReducedOrderResult r = homogenize::addReducedOrderEntry(
      spec, cell, cli.name, reducedOrderOptions(cli, names), lib, cli.overwrite);
  if (cli.shared.json) {
    std::cout << homogenize::reducedOrderJson(cli.name, r, lib.path()).dump() << std::endl;
    return;
  }
  std::printf("%s", homogenize::reducedOrderSummary(cli.name, r).c_str());
  std::printf("added '%s' to %s\n", cli.name.c_str(), lib.path().string().c_str());
}

/// The linear homogenization into the library (distributed under mpirun).
void runLinear(const Cli& cli, const lamina::micro::CellSpec& spec,
               const lamina::micro::UnitCell& cell, const lamina::homogenize::MpiSession& mpi) {
  using namespace lamina;
  if (cli.name.empty())
    throw Error("--name NAME is required");
  materials::Library lib(materials::Library::resolvePath(cli.shared.library));
  const homogenize::Options opt = linearOptions(cli, cli.shared.quiet || mpi.rank() != 0);
  const homogenize::Distribution dist = homogenize::Distribution::world(homogenize::gridOf(cell));
  homogenize::homogenizeIntoLibrary(
      spec, cell, cli.name, opt, lib, cli.overwrite,
      [&](const homogenize::EntryResult& e) {
        if (cli.shared.json)
          std::cout << homogenize::toJson(e, lib.path()).dump() << std::endl;
        else
          printHuman(e, cell, lib.path().string());
      },
      &dist);
}

/// The method: check the options, read the cell, size it, build it, run.
void run(Cli& cli, const CliNames& names, lamina::homogenize::MpiSession& mpi) {
  using namespace lamina;
  if (!cli.name.empty()) // a nonlinear run without a library entry has none
    core::checkName(cli.name, "entry name", {"", 0, "--name"});
  core::checkThreads(cli.shared.threads, "--threads");
  const micro::CellSpec spec =
      micro::readCell(cli.cell_path, micro::lazyCatalog(cli.shared.catalog), cli.shared.overrides);
  std::array<int, 3> n = spec.resolution;
  if (cli.resolution > 0)
    n = {cli.resolution, cli.resolution, cli.resolution};
  if (cli.nonlinear())
    checkNonlinear(cli, spec);
  if (cli.reduced_order)
    checkReducedOrder(cli, spec, n, mpi);
  else
    checkMemory(cli, spec, n, mpi);
  const micro::UnitCell cell = buildCell(spec, n, mpi);
  if (cli.reduced_order)
    runReducedOrder(cli, names, spec, cell);
  else if (cli.nonlinear())
    runNonlinear(cli, spec, cell, mpi);
  else
    runLinear(cli, spec, cell, mpi);
}

} // namespace

namespace lamina::homogenize {

int runProgram(int argc, char** argv, MpiSession& mpi, UnexpectedErrors unexpected) {
  CLI::App app{"homogenize: effective stiffness and density of a voxel unit cell "
               "(mpirun -np N homogenize ... runs it over N MPI ranks)"};
  Cli cli;
  CliNames names;
  addOptions(app, cli, names);
  try {
    app.parse(argc, argv);
    parseChoices(names, cli);
    checkReducedOrderOptions(cli, names); // first: a mode of its own
    checkPathOptions(cli, names);
  } catch (const CLI::ParseError& e) {
    // every rank parses the same arguments: one prints
    if (mpi.rank() != 0)
      return e.get_exit_code() == 0 ? 0 : lamina::kExitUsage;
    return lamina::core::reportUsageError(app, e, "homogenize");
  }
  try {
    run(cli, names, mpi);
  } catch (const lamina::DivergenceError& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return mpi.abort(lamina::kExitDivergence);
  } catch (const lamina::Error& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return mpi.abort(lamina::kExitUserError);
  } catch (const std::exception& e) {
    if (unexpected == UnexpectedErrors::Rethrow)
      throw;
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return mpi.abort(lamina::kExitUserError);
  } catch (...) {
    if (unexpected == UnexpectedErrors::Rethrow)
      throw;
    std::fprintf(stderr, "homogenize: unexpected error (not a std::exception)\n");
    return mpi.abort(lamina::kExitUserError);
  }
  return 0;
}

} // namespace lamina::homogenize
