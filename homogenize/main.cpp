/// @file main.cpp
/// @brief `homogenize CELL.toml --name NAME [--library PATH] [--json]
/// [--threads N] [--tol T] [--resolution N]`: effective C and density of a
/// unit cell into the materials library. With `--path P --rate R --to S`:
/// the nonlinear cell under that strain-rate history (nonlinear_run.hpp).
/// Under `mpirun -np N` the linear homogenization runs over N ranks (rank 0
/// builds the cell, scatters it, prints and writes the library).

#include "core/error.hpp"
#include "core/names.hpp"
#include "core/resources.hpp"
#include "homogenize/distribution.hpp"
#include "homogenize/homogenizer.hpp"
#include "homogenize/library_entry.hpp"
#include "homogenize/nonlinear_run.hpp"
#include "materials/library.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace {

void printDispersion(const lamina::homogenize::EntryResult& e) {
  if (!e.dispersion) {
    std::printf("no micro-inertia: the cell has no size in metres ([cell] size)\n");
    return;
  }
  const auto& d = *e.dispersion;
  std::printf("dispersion zeta^2 D_lin (kg/m, lamina order; eqs. 38-39):\n");
  for (int i = 0; i < 6; ++i) {
    std::printf("  ");
    for (int j = 0; j < 6; ++j)
      std::printf(" %12.5g", d.D(i, j));
    std::printf("\n");
  }
  std::printf("eq. 39 least-squares residual per load case");
  for (double r : d.residual)
    std::printf(" %.2g", r);
  std::printf("\ncharacteristic length sqrt(zeta^2 D_II / rho) (m):");
  for (int i = 0; i < 6; ++i)
    std::printf(" %.3g", std::sqrt(std::max(0.0, d.D(i, i)) / e.result.density));
  std::printf("\n");
}

void printHuman(const lamina::homogenize::EntryResult& e, const lamina::micro::UnitCell& cell,
                const std::string& library) {
  const std::string& name = e.name;
  const lamina::homogenize::Result& r = e.result;
  std::printf("%s: %zu voxels (%d x %d x %d), density %.6g kg/m^3\n", name.c_str(), r.voxels,
              cell.n[0], cell.n[1], cell.n[2], r.density);
  std::printf("C (GPa, lamina order xx yy zz xy yz xz, engineering shear):\n");
  for (int i = 0; i < 6; ++i) {
    std::printf("  ");
    for (int j = 0; j < 6; ++j)
      std::printf(" %12.6g", r.C(i, j) * 1e-9);
    std::printf("\n");
  }
  std::printf("load cases: iterations");
  for (int it : r.iterations())
    std::printf(" %d", it);
  std::printf(", final residuals");
  for (const auto& c : r.cases)
    std::printf(" %.2g", c.residual);
  std::printf("\n");
  std::printf("asymmetry before symmetrizing %.3g, symmetry %s (tol %.1g), wall %.2f s\n",
              r.asymmetry, lamina::materials::toString(r.symmetry.cls).c_str(), r.symmetry_tol,
              r.wall_s);
  printDispersion(e);
  std::printf("added '%s' to %s\n", name.c_str(), library.c_str());
}

} // namespace

int main(int argc, char** argv) {
  lamina::homogenize::MpiSession mpi(&argc, &argv);
  CLI::App app{"homogenize: effective stiffness and density of a voxel unit cell "
               "(mpirun -np N homogenize ... runs it over N MPI ranks)"};
  std::string cell_path, name, library, catalog;
  bool json = false, overwrite = false, quiet = false;
  std::string plan = "auto", estimate = "energy", precision = "auto";
  int threads = 0, resolution = 0;
  double tol = 1e-5;
  app.add_option("cell", cell_path, "cell file (TOML)")->required();
  app.add_option(
      "--name", name,
      "library entry name (with a J sweep: NAME-J<J>; with --tangent-rates: NAME-R<rate>)");
  app.add_option("--library", library, "library file (default: $LAMINA_LIBRARY, XDG data dir)");
  app.add_flag("--json", json, "print a JSON summary on stdout (one object per entry)");
  app.add_option("--threads", threads, "OpenMP and FFTW threads")->check(CLI::NonNegativeNumber);
  app.add_option("--tol", tol, "relative residual per load case")->check(CLI::PositiveNumber);
  app.add_option("--resolution", resolution, "override the resolution: N^3 voxels")
      ->check(CLI::Range(2, 4096));
  app.add_option("--catalog", catalog, "catalog file (default: $LAMINA_CATALOG or built-in)");
  app.add_flag("--overwrite", overwrite, "replace an existing entry of the same name");
  app.add_option("--fftw-plan", plan,
                 "FFTW planning: estimate, measure (wisdom cached in ~/.cache/lamina), "
                 "auto (measure above 64^3)")
      ->check(CLI::IsMember({"auto", "estimate", "measure"}));
  app.add_option("--estimate", estimate,
                 "C from the six solutions: energy (<eps_j:C:eps_k>, error quadratic in the "
                 "residual, keeps 6 displacement fields) or stress (<sigma_k>, least memory)")
      ->check(CLI::IsMember({"energy", "stress"}));
  app.add_option("--precision", precision,
                 "FFT precision of the preconditioner: auto (single when tol >= 1e-6), single, "
                 "double")
      ->check(CLI::IsMember({"auto", "single", "double"}));
  app.add_flag("--quiet", quiet, "no progress line");
  // nonlinear: the cell under a strain-rate history (docs/homogenize.md)
  std::string path_name, out;
  lamina::homogenize::PathSpec path;
  lamina::homogenize::TangentSpec tangent;
  std::vector<int> field_steps;
  double eta = 0.1;
  auto* path_opt =
      app.add_option("--path", path_name,
                     "nonlinear run: uniaxial-strain | shear | confined | uniaxial-stress")
          ->check(CLI::IsMember({"uniaxial-stress", "uniaxial-strain", "shear", "confined"}));
  app.add_option("--rate", path.rate, "nonlinear: driven strain rate (1/s)")
      ->check(CLI::PositiveNumber);
  app.add_option("--to", path.to, "nonlinear: final driven strain")->check(CLI::PositiveNumber);
  app.add_option("--steps", path.steps, "nonlinear: load steps per leg (default 100)")
      ->check(CLI::Range(1, 10000000));
  app.add_flag("--unload", path.unload, "nonlinear: back to zero strain at the same rate");
  app.add_option("--out", out, "nonlinear: history CSV (also OUT-phases.csv, OUT-fields.h5)");
  app.add_option("--fields", field_steps, "nonlinear: steps whose fields are written (XDMF)")
      ->delimiter(',');
  app.add_option("--eta", eta, "nonlinear: CG forcing term per Newton step (default 0.1)")
      ->check(CLI::Range(1e-12, 0.9));
  app.add_option("--tangent-rates", tangent.rates,
                 "rates (1/s, inf allowed) of effective tangent entries NAME-R<rate>")
      ->delimiter(',');
  app.add_option("--tangent-strain", tangent.strain,
                 "driven strain of the state of the tangent entries (default 0)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--tangent-increment", tangent.increment,
                 "strain increment a tangent is for: dt = increment / rate (default 1e-3)")
      ->check(CLI::PositiveNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // every rank parses the same arguments: one prints
    if (mpi.rank() != 0)
      return e.get_exit_code() == 0 ? 0 : lamina::kExitUsage;
    return app.exit(e) == 0 ? 0 : lamina::kExitUsage;
  }
  try {
    using namespace lamina;
    if (!name.empty()) // a nonlinear run without a library entry has none
      core::checkName(name, "entry name", {"", 0, "--name"});
    core::checkThreads(threads, "--threads");
    const micro::CellSpec spec = micro::readCell(cell_path, micro::lazyCatalog(catalog));
    std::array<int, 3> n = spec.resolution;
    if (resolution > 0)
      n = {resolution, resolution, resolution};
    // checked before anything large is allocated (docs/homogenize.md,
    // Memory): per voxel 72 bytes of CG vectors, the FFT buffer, the phase
    // index and with the energy estimate six displacement fields, over the
    // ranks; rank 0 also holds the whole phase map while it scatters it
    const std::uint64_t voxels = static_cast<std::uint64_t>(n[0]) *
                                 static_cast<std::uint64_t>(n[1]) *
                                 static_cast<std::uint64_t>(n[2]);
    const bool single =
        precision == "single" ||
        (precision == "auto" && homogenize::autoPrecision(tol) == homogenize::Precision::Single);
    const std::uint64_t per_voxel = 76 + (single ? 12 : 24) + (estimate == "energy" ? 144 : 0);
    // a cell with a size also gets its dispersion tensor, formed on rank 0
    // from the whole grid: the spectra h_hat of the six cases (6 x 3 complex
    // doubles per mode of the half spectrum, 146 bytes per voxel), the FFT
    // buffer and the density spectrum (32), the gathered displacement of a
    // case when distributed (24)
    const std::uint64_t dispersion_per_voxel =
        spec.physical_size ? 180 + (mpi.ranks() > 1 ? 24 : 0) : 0;
    core::requireMemory(double(voxels * per_voxel / static_cast<std::uint64_t>(mpi.ranks()) +
                               (mpi.rank() == 0 ? (8 + dispersion_per_voxel) * voxels : 0)),
                        "homogenizing " + std::to_string(n[0]) + " x " + std::to_string(n[1]) +
                            " x " + std::to_string(n[2]) + " voxels",
                        {cell_path, 0, resolution > 0 ? "--resolution" : "cell.resolution"},
                        "run it distributed: mpirun -np N homogenize " + cell_path +
                            " ... (each rank holds 1/N of the fields), or --estimate stress "
                            "--precision single (90 bytes per voxel)");
    // rank 0 builds the phase map; the others learn only its grid
    micro::UnitCell cell;
    if (mpi.rank() == 0)
      cell = micro::buildCell(spec, n);
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
    if (!path_name.empty() || !tangent.rates.empty()) {
      LAMINA_CHECK(mpi.ranks() == 1, "nonlinear runs are serial (no mpirun)");
      path.path = *materials::parseDrivePath(path_name.empty() ? "uniaxial-strain" : path_name);
      homogenize::NonlinearOptions nl;
      nl.tol = tol;
      nl.eta = eta;
      nl.threads = threads;
      nl.measure = plan == "auto" ? -1 : plan == "measure" ? 1 : 0;
      if (path_opt->count() > 0 && !out.empty()) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto steps = homogenize::runPath(
            spec, cell, path, nl, out, field_steps, [&](const homogenize::StepResult& r) {
              if (!quiet)
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
                    steps.size(), path_name.c_str(), path.rate, cell.n[0], cell.n[1], cell.n[2],
                    newton, krylov,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                    out.c_str());
      } else if (path_opt->count() > 0 && tangent.rates.empty()) {
        throw Error("a nonlinear run needs --out FILE.csv (or --tangent-rates)");
      }
      if (!tangent.rates.empty()) {
        if (name.empty())
          throw Error("--tangent-rates needs --name NAME");
        tangent.path = path;
        materials::Library lib(materials::Library::resolvePath(library));
        homogenize::addTangentEntries(
            spec, cell, name, tangent, nl, lib, overwrite, [&](const materials::Material& m) {
              std::printf("added '%s' to %s\n", m.name.c_str(), lib.path().string().c_str());
            });
      }
      return 0;
    }
    if (name.empty())
      throw Error("--name NAME is required");
    materials::Library lib(materials::Library::resolvePath(library));
    homogenize::Options opt;
    opt.tol = tol;
    opt.threads = threads;
    opt.measure = plan == "auto" ? -1 : plan == "measure" ? 1 : 0;
    opt.quiet = quiet || mpi.rank() != 0;
    opt.estimate =
        estimate == "stress" ? homogenize::Estimate::Stress : homogenize::Estimate::Energy;
    if (precision != "auto")
      opt.precision =
          precision == "single" ? homogenize::Precision::Single : homogenize::Precision::Double;
    const homogenize::Distribution dist = homogenize::Distribution::world(homogenize::gridOf(cell));
    homogenize::homogenizeIntoLibrary(
        spec, cell, name, opt, lib, overwrite,
        [&](const homogenize::EntryResult& e) {
          if (json)
            std::cout << homogenize::toJson(e).dump() << std::endl;
          else
            printHuman(e, cell, lib.path().string());
        },
        &dist);
  } catch (const lamina::DivergenceError& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return mpi.abort(lamina::kExitDivergence);
  } catch (const lamina::Error& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return mpi.abort(lamina::kExitUserError);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return mpi.abort(lamina::kExitUserError);
  }
  return 0;
}
