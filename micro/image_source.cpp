#include "micro/image_source.hpp"

#include "core/toml_reader.hpp"

#include <cmath>
#include <optional>

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

} // namespace lamina::micro
