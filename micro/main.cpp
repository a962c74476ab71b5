/// @file main.cpp
/// @brief `micro CELL.toml --out PHASES.h5|.vti|.raw|.tif`: builds a unit
/// cell (generated or from an image), writes its phase map (HDF5 + XDMF, or
/// an image in the same formats image cells read: the labels are the phase
/// ids) and prints the volume fractions reached.

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "materials/catalog.hpp"
#include "micro/cell.hpp"
#include "micro/image_cell.hpp"
#include "micro/phase_map_io.hpp"
#include "micro/unit_cell.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
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

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"micro: build a voxel unit cell and write its phase map"};
  std::string cell_path, out, catalog;
  std::string encoding = "appended";
  bool zlib = false;
  int resolution = 0;
  app.add_option("cell", cell_path, "cell file (TOML)")->required();
  app.add_option("--out", out,
                 "phase map: .h5 (+ .xdmf beside it), .vti, .raw or .tif (labels = phase ids)")
      ->required();
  app.add_option("--vti-encoding", encoding, "VTI data: ascii, binary (base64) or appended (raw)")
      ->check(CLI::IsMember(lamina::micro::kVtiEncodingNames.names()));
  app.add_flag("--zlib", zlib, "VTI binary/appended: zlib-compressed blocks");
  app.add_option("--resolution", resolution, "override the cell's resolution (N^3 voxels)");
  app.add_option("--catalog", catalog, "catalog file (default: $LAMINA_CATALOG or the built-in)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : lamina::kExitUsage;
  }
  try {
    using namespace lamina::micro;
    const CellSpec spec = readCell(cell_path, lazyCatalog(catalog));
    checkOutputs(out, spec, cell_path, catalog); // before anything is built
    std::array<int, 3> n = spec.resolution;
    if (resolution > 0)
      n = {resolution, resolution, resolution};
    const UnitCell cell = buildCell(spec, n);
    std::vector<std::string> names;
    for (const auto& p : spec.phases)
      names.push_back(p.name);
    ImageFormat format = ImageFormat::Hdf5;
    if (!formatFromExtension(out, format))
      throw lamina::Error("--out: cannot tell the format from the extension (expected " +
                              kImageExtensions.list() + ")",
                          {out, 0, "--out"});
    const VoxelImage labels = labelImage(spec, cell);
    std::string keys;
    if (format == ImageFormat::Hdf5) {
      UnitCell labelled = cell; // the HDF5 phase map holds the phase ids too
      labelled.phase = labels.value;
      writePhaseMap(labelled, names, out);
      keys = "image = \"" + std::filesystem::path(out).filename().string() +
             "\"\ndataset = \"/phases\"\n";
    } else {
      ImageWriteOptions wo;
      wo.vti = *kVtiEncodingNames.parse(encoding); // checked by CLI::IsMember
      wo.zlib = zlib;
      keys = writeImage(labels, out, format, wo);
    }
    std::printf("cell %s: %d x %d x %d voxels, %zu inclusions\n", cell_path.c_str(), n[0], n[1],
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
    std::printf("wrote %s; an image cell reads it back with the [cell] keys\n%s", out.c_str(),
                keys.c_str());
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
