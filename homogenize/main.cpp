/// @file main.cpp
/// @brief `homogenize CELL.toml --name NAME [--library PATH] [--json]
/// [--threads N] [--tol T] [--resolution N]`: effective C and density of a
/// unit cell into the materials library.

#include "core/error.hpp"
#include "core/names.hpp"
#include "core/resources.hpp"
#include "homogenize/homogenizer.hpp"
#include "homogenize/library_entry.hpp"
#include "materials/library.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace {

/// Memory the homogenizer needs per voxel, bytes: peak resident size of
/// `homogenize cases/cells/sphere.toml --threads 1` grows by 109 B per voxel
/// from --resolution 32 to 64 (/usr/bin/time -f %M); 128 with margin.
constexpr double kBytesPerVoxel = 128;

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
  CLI::App app{"homogenize: effective stiffness and density of a voxel unit cell"};
  std::string cell_path, name, library, catalog;
  bool json = false, overwrite = false, quiet = false;
  std::string plan = "auto";
  int threads = 0, resolution = 0;
  double tol = 1e-5;
  app.add_option("cell", cell_path, "cell file (TOML)")->required();
  app.add_option("--name", name, "library entry name (with a J sweep: NAME-J<J>)")->required();
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
  app.add_flag("--quiet", quiet, "no progress line");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : lamina::kExitUsage;
  }
  try {
    using namespace lamina;
    core::checkName(name, "entry name", {"", 0, "--name"});
    core::checkThreads(threads, "--threads");
    const micro::CellSpec spec = micro::readCell(cell_path, micro::lazyCatalog(catalog));
    std::array<int, 3> n = spec.resolution;
    if (resolution > 0)
      n = {resolution, resolution, resolution};
    const double voxels = double(n[0]) * double(n[1]) * double(n[2]);
    core::requireMemory(kBytesPerVoxel * voxels,
                        "homogenizing " + std::to_string(n[0]) + " x " + std::to_string(n[1]) +
                            " x " + std::to_string(n[2]) + " voxels",
                        {cell_path, 0, resolution > 0 ? "--resolution" : "cell.resolution"});
    const micro::UnitCell cell = micro::buildCell(spec, n);
    materials::Library lib(materials::Library::resolvePath(library));
    homogenize::Options opt;
    opt.tol = tol;
    opt.threads = threads;
    opt.measure = plan == "auto" ? -1 : plan == "measure" ? 1 : 0;
    opt.quiet = quiet;
    homogenize::homogenizeIntoLibrary(spec, cell, name, opt, lib, overwrite,
                                      [&](const homogenize::EntryResult& e) {
                                        if (json)
                                          std::cout << homogenize::toJson(e).dump() << std::endl;
                                        else
                                          printHuman(e, cell, lib.path().string());
                                      });
  } catch (const lamina::DivergenceError& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return lamina::kExitDivergence;
  } catch (const lamina::Error& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return lamina::kExitUserError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "homogenize: %s\n", e.what());
    return lamina::kExitUserError;
  }
  return 0;
}
