#include "micro/image_cell.hpp"

#include "core/error.hpp"
#include "core/toml_reader.hpp"

#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>

namespace lamina::micro {

namespace {

constexpr const char* kImageKeys[] = {"format",     "dataset",    "axes",         "dimensions",
                                      "type",       "byte_order", "header_bytes", "crop",
                                      "downsample", "voxel_size"};

/// byte_order of a raw image.
enum class ByteOrder { Little, Big };
constexpr auto kByteOrderNames =
    core::enumNames<ByteOrder>({{"little", ByteOrder::Little}, {"big", ByteOrder::Big}});

std::array<int, 3> readCounts(const core::TableReader& t, const std::string& key, int min) {
  const auto v = t.getDoubleArray(key);
  if (v.size() != 3)
    t.fail(key, "must give 3 integers [x, y, z]");
  std::array<int, 3> out{};
  for (std::size_t d = 0; d < 3; ++d) {
    if (v[d] != std::floor(v[d]) || v[d] < min || v[d] > 1e9)
      t.fail(key, "must be integers >= " + std::to_string(min));
    out[d] = static_cast<int>(v[d]);
  }
  return out;
}

} // namespace

bool hasImageKey(const core::TableReader& c, std::string& key) {
  for (const char* k : kImageKeys)
    if (c.has(k)) {
      key = k;
      return true;
    }
  return false;
}

ImageSource readImageSource(const core::TableReader& c, const std::string& cell_file) {
  ImageSource s;
  s.cell_file = cell_file;
  const std::string rel = c.getString("image");
  if (rel.empty())
    c.fail("image", "must name an image file");
  s.path = std::filesystem::path(cell_file).parent_path() / rel;
  if (c.has("format")) {
    const std::string f = c.getString("format");
    const std::optional<ImageFormat> format = kImageFormatNames.parse(f);
    if (!format)
      c.fail("format",
             "unknown image format '" + f + "' (expected " + kImageFormatNames.list() + ")");
    s.format = *format;
  } else if (!formatFromExtension(s.path, s.format)) {
    c.fail("image", "cannot tell the format of '" + rel + "' from its extension (" +
                        kImageExtensions.list() + "): give format = \"...\"");
  }
  const bool raw = s.format == ImageFormat::Raw;
  for (const char* k : {"type", "byte_order", "header_bytes"})
    if (!raw && c.has(k))
      c.fail(k, std::string("applies to raw images only (this one is ") + toString(s.format) + ")");
  if (c.has("dataset")) {
    if (s.format != ImageFormat::Hdf5 && s.format != ImageFormat::Vti)
      c.fail("dataset", "applies to HDF5 (dataset path) and VTI (array name) images only");
    s.dataset = c.getString("dataset");
    if (s.format == ImageFormat::Hdf5 && (s.dataset.empty() || s.dataset[0] != '/'))
      c.fail("dataset", "an HDF5 dataset path starts with '/' (e.g. \"/phases\")");
  }
  // raw: the layout of the file; any other format: checked against its header
  if (c.has("dimensions"))
    s.dimensions = readCounts(c, "dimensions", 1);
  if (raw) {
    if (!c.has("dimensions"))
      c.fail("dimensions", "a raw image needs dimensions = [Nx, Ny, Nz]");
    const std::string t = c.getString("type");
    const std::optional<ScalarType> type = kScalarTypeNames.parse(t);
    if (!type)
      c.fail("type", "unknown type '" + t + "' (expected " + kScalarTypeNames.list() + ")");
    s.type = *type;
    s.big_endian = c.getChoice("byte_order", kByteOrderNames, ByteOrder::Little) == ByteOrder::Big;
    const auto hb = c.getInt("header_bytes", 0);
    if (hb < 0)
      c.fail("header_bytes", "must not be negative");
    s.header_bytes = static_cast<std::uint64_t>(hb);
  }
  s.axes = raw ? AxisOrder::Zyx : AxisOrder::Xyz;
  if (c.has("axes")) {
    if (s.format != ImageFormat::Hdf5 && !raw)
      c.fail("axes", "applies to HDF5 and raw images (VTI and TIFF store x fastest)");
    // "xyz": x slowest, "zyx": x fastest
    s.axes = c.getChoice("axes", kAxisOrderNames, s.axes);
  }
  if (auto crop = c.optionalTable("crop")) {
    s.crop_start = crop->has("start") ? readCounts(*crop, "start", 0) : std::array<int, 3>{};
    s.crop_count = crop->has("count") ? readCounts(*crop, "count", 1) : std::array<int, 3>{};
  }
  const auto f = c.getInt("downsample", 1);
  if (f < 1 || f > 64)
    c.fail("downsample", "must be an integer in [1, 64]");
  s.downsample = static_cast<int>(f);
  return s;
}

std::vector<std::int32_t> phaseLabels(const CellSpec& spec) {
  std::vector<std::int32_t> out;
  for (std::size_t p = 0; p < spec.phases.size(); ++p)
    out.push_back(spec.phases[p].id ? *spec.phases[p].id : static_cast<std::int32_t>(p));
  return out;
}

UnitCell buildImageCell(const CellSpec& spec) {
  LAMINA_CHECK(spec.image.has_value(), "not an image cell");
  const ImageSource& src = *spec.image;
  VoxelImage img = readImage(src);
  UnitCell cell;
  cell.n = img.n;
  cell.phase_count = static_cast<int>(spec.phases.size());
  if (spec.voxel_size)
    cell.size = spec.voxel_size->cwiseProduct(Eigen::Vector3d(img.n[0], img.n[1], img.n[2]));
  else if (spec.physical_size)
    cell.size = spec.size;
  else if (img.spacing)
    cell.size = img.spacing->cwiseProduct(Eigen::Vector3d(img.n[0], img.n[1], img.n[2]));
  else
    cell.size = Eigen::Vector3d(img.n[0], img.n[1], img.n[2]);
  std::unordered_map<std::int32_t, std::int32_t> phase_of;
  const auto labels = phaseLabels(spec);
  for (std::size_t p = 0; p < labels.size(); ++p)
    phase_of[labels[p]] = static_cast<std::int32_t>(p);
  std::map<std::int32_t, std::size_t> orphans;
  cell.phase.resize(img.voxels());
  for (std::size_t v = 0; v < img.voxels(); ++v) {
    const auto it = phase_of.find(img.value[v]);
    if (it == phase_of.end())
      ++orphans[img.value[v]];
    else
      cell.phase[v] = it->second;
  }
  if (!orphans.empty()) {
    std::string list, owned;
    for (const auto& [label, count] : orphans)
      list += (list.empty() ? "" : ", ") + std::to_string(label) + " (" + std::to_string(count) +
              " voxels)";
    for (std::size_t p = 0; p < labels.size(); ++p)
      owned +=
          (owned.empty() ? "" : ", ") + spec.phases[p].name + " = " + std::to_string(labels[p]);
    throw Error("image " + src.path.string() + " holds values no phase owns: " + list +
                    "; give each a [[phases]] table with id = VALUE (ids now: " + owned + ")",
                {spec.file, 0, "phases"});
  }
  cell.countFractions();
  return cell;
}

VoxelImage labelImage(const CellSpec& spec, const UnitCell& cell) {
  VoxelImage img;
  img.n = cell.n;
  img.spacing = cell.size.cwiseQuotient(Eigen::Vector3d(cell.n[0], cell.n[1], cell.n[2]));
  const auto labels = phaseLabels(spec);
  img.value.resize(cell.voxels());
  for (std::size_t v = 0; v < cell.voxels(); ++v)
    img.value[v] = labels[static_cast<std::size_t>(cell.phase[v])];
  return img;
}

} // namespace lamina::micro
