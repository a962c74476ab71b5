/// @file main.cpp
/// @brief `micro CELL.toml --out PHASES.h5|.vti|.raw|.tif [--set KEY=VALUE]
/// [--json]`: builds a unit
/// cell (generated or from an image), writes its phase map (HDF5 + XDMF, or
/// an image in the same formats image cells read: the labels are the phase
/// ids) and prints the volume fractions reached.

#include "core/atomic_file.hpp"
#include "core/command_line.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/parallel.hpp"
#include "core/resources.hpp"
#include "materials/catalog.hpp"
#include "micro/cell.hpp"
#include "micro/image_cell.hpp"
#include "micro/phase_map_io.hpp"
#include "micro/unit_cell.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <vector>

namespace {

/// Refuses @p out (and the .xdmf beside an .h5) when it is not a regular
/// file or is one of the run's inputs: the cell file, the catalog, the image.
void checkOutputs(const std::string& out, const lamina::micro::CellSpec& spec,
                  const std::string& cell_path, const std::string& catalog) {
  std::vector<std::filesystem::path> inputs{
      cell_path,
      catalog.empty() ? lamina::materials::Catalog::defaultPath() : std::filesystem::path(catalog)};
  if (spec.image)
    inputs.push_back(spec.image->path);
  lamina::core::checkOutput(out, inputs, "--out");
  lamina::micro::ImageFormat format = lamina::micro::ImageFormat::Hdf5;
  if (lamina::micro::formatFromExtension(out, format) &&
      format == lamina::micro::ImageFormat::Hdf5) {
    std::filesystem::path xdmf = out;
    lamina::core::checkOutput(xdmf.replace_extension(".xdmf"), inputs, "--out (its .xdmf)");
  }
}

/// The command line, parsed.
struct Args {
  std::string cell_path, out;
  std::string encoding = "appended";
  bool zlib = false;
  int resolution = 0;
  lamina::core::SharedOptions shared; ///< --catalog, --set, --threads, --json
};

/// Declares the options of micro on @p app, into @p a.
void addOptions(CLI::App& app, Args& a) {
  lamina::core::showDefaults(app);
  app.add_option("cell", a.cell_path, "cell file (TOML)")->required();
  app.add_option("--out", a.out,
                 "phase map: .h5 (+ .xdmf beside it), .vti, .raw or .tif (labels = phase ids)")
      ->required();
  app.add_option("--vti-encoding", a.encoding,
                 "VTI data: ascii, binary (base64) or appended (raw)")
      ->check(CLI::IsMember(lamina::micro::kVtiEncodingNames.names()));
  app.add_flag("--zlib", a.zlib, "VTI binary/appended: zlib-compressed blocks");
  app.add_option("--resolution", a.resolution,
                 "override the cell's resolution: N^3 voxels (default: the cell's)")
      ->check(CLI::Range(2, 4096))
      ->default_str("");
  using lamina::core::Shared;
  lamina::core::addSharedOptions(app, a.shared,
                                 Shared::Catalog | Shared::Set | Shared::Threads | Shared::Json);
}

/// Writes the phase map of @p cell to @p a.out; @return the [cell] keys
/// with which an image cell reads it back.
std::string writeLabels(const Args& a, const lamina::micro::CellSpec& spec,
                        const lamina::micro::UnitCell& cell) {
  using namespace lamina::micro;
  std::vector<std::string> names;
  for (const auto& p : spec.phases)
    names.push_back(p.name);
  ImageFormat format = ImageFormat::Hdf5;
  if (!formatFromExtension(a.out, format))
    throw lamina::Error("--out: cannot tell the format from the extension (expected " +
                            kImageExtensions.list() + ")",
                        {a.out, 0, "--out"});
  const VoxelImage labels = labelImage(spec, cell);
  if (format == ImageFormat::Hdf5) {
    UnitCell labelled = cell; // the HDF5 phase map holds the phase ids too
    labelled.phase = labels.value;
    writePhaseMap(labelled, names, a.out);
    return "image = \"" + std::filesystem::path(a.out).filename().string() +
           "\"\ndataset = \"/phases\"\n";
  }
  ImageWriteOptions wo;
  wo.vti = *kVtiEncodingNames.parse(a.encoding); // checked by CLI::IsMember
  wo.zlib = a.zlib;
  return writeImage(labels, a.out, format, wo);
}

/// Prints what was built and written: text, or one JSON object (--json).
void printSummary(const Args& a, const lamina::micro::CellSpec& spec,
                  const lamina::micro::UnitCell& cell, const std::string& keys) {
  using namespace lamina::micro;
  const auto& n = cell.n;
  if (a.shared.json) {
    nlohmann::json j{{"cell", a.cell_path},
                     {"voxels", {n[0], n[1], n[2]}},
                     {"inclusions", cell.inclusions.size()},
                     {"out", a.out},
                     {"image_keys", keys}};
    for (std::size_t g = 0; g < spec.groups.size(); ++g)
      j["groups"].push_back(
          {{"key", spec.groups[g].key},
           {"shape", toString(spec.groups[g].prototype.shape)},
           {"target_fraction", std::isnan(cell.target_fraction[g])
                                   ? nlohmann::json(nullptr)
                                   : nlohmann::json(cell.target_fraction[g])},
           {"analytic_fraction", cell.analytic_fraction[g]}});
    for (std::size_t p = 0; p < spec.phases.size(); ++p)
      j["phases"].push_back(
          {{"name", spec.phases[p].name}, {"voxel_fraction", cell.voxel_fraction[p]}});
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("cell %s: %d x %d x %d voxels, %zu inclusions\n", a.cell_path.c_str(), n[0], n[1],
              n[2], cell.inclusions.size());
  for (std::size_t g = 0; g < spec.groups.size(); ++g)
    std::printf("  %s (%s): target fraction %s, analytic %s\n", spec.groups[g].key.c_str(),
                toString(spec.groups[g].prototype.shape).c_str(),
                std::isnan(cell.target_fraction[g])
                    ? "-"
                    : lamina::core::formatShort(cell.target_fraction[g]).c_str(),
                lamina::core::formatShort(cell.analytic_fraction[g]).c_str());
  for (std::size_t p = 0; p < spec.phases.size(); ++p)
    std::printf("  phase %zu %-16s voxel fraction %s\n", p, spec.phases[p].name.c_str(),
                lamina::core::formatShort(cell.voxel_fraction[p]).c_str());
  std::printf("wrote %s; an image cell reads it back with the [cell] keys\n%s", a.out.c_str(),
              keys.c_str());
}

/// Reads, builds and writes the cell of @p a.
void run(const Args& a) {
  using namespace lamina::micro;
  lamina::core::checkThreads(a.shared.threads, "--threads");
  const CellSpec spec =
      readCell(a.cell_path, lazyCatalog(a.shared.catalog), a.shared.overrides);
  checkOutputs(a.out, spec, a.cell_path, a.shared.catalog); // before anything is built
  std::array<int, 3> n = spec.resolution;
  if (a.resolution > 0)
    n = {a.resolution, a.resolution, a.resolution};
  std::optional<lamina::core::ThreadsScope> threads;
  if (a.shared.threads > 0)
    threads.emplace(a.shared.threads);
  const UnitCell cell = buildCell(spec, n);
  printSummary(a, spec, cell, writeLabels(a, spec, cell));
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"micro: build a voxel unit cell and write its phase map"};
  Args args;
  addOptions(app, args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return lamina::core::reportUsageError(app, e, "micro");
  }
  try {
    run(args);
  } catch (const lamina::Error& e) {
    std::fprintf(stderr, "micro: %s\n", e.what());
    return lamina::kExitUserError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "micro: %s\n", e.what());
    return lamina::kExitUserError;
  } catch (...) {
    std::fputs("micro: unexpected error (not a std::exception)\n", stderr);
    return lamina::kExitUserError;
  }
  return 0;
}
