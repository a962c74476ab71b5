#include "micro/image_io.hpp"

#include "core/parallel.hpp"
#include "core/resources.hpp"
#include "micro/image_formats.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <optional>

namespace lamina::micro {

bool formatFromExtension(const std::filesystem::path& path, ImageFormat& out) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::optional<ImageFormat> format = kImageExtensions.parse(ext);
  if (format)
    out = *format;
  return format.has_value();
}

std::string toString(ImageFormat f) {
  return std::string(kImageFormatNames.name(f));
}

std::string toString(ScalarType t) {
  return std::string(kScalarTypeNames.name(t));
}

int bytesOf(ScalarType t) {
  switch (t) {
  case ScalarType::Int8:
  case ScalarType::UInt8:
    return 1;
  case ScalarType::Int16:
  case ScalarType::UInt16:
    return 2;
  case ScalarType::Int32:
  case ScalarType::UInt32:
    return 4;
  case ScalarType::Int64:
  case ScalarType::UInt64:
    return 8;
  }
  return 0;
}

namespace detail {

void imageError(const ImageSource& src, const std::string& message) {
  throw Error(message + " (image " + src.path.string() + ")", {src.cell_file, 0, src.key});
}

core::InputFile openImage(const ImageSource& src) {
  std::error_code ec;
  if (!std::filesystem::exists(src.path, ec))
    imageError(src, "image file not found");
  return core::InputFile(src.path, "image", core::kMaxImageBytes, {src.cell_file, 0, src.key});
}

void checkImageMemory(const ImageSource& src, std::size_t voxels, std::size_t bytes_per_voxel) {
  // the file's bytes plus the int32 labels plus one reordered/cropped copy
  const double need = static_cast<double>(voxels) * static_cast<double>(bytes_per_voxel + 8);
  core::requireMemory(
      need, "reading image " + src.path.string() + " (" + std::to_string(voxels) + " voxels)",
      {src.cell_file, 0, src.key},
      "crop it (crop = { start = [...], count = [...] }), down-sample it "
      "(downsample = 2), or run distributed: mpirun -np N homogenize CELL ...");
}

namespace {
template <typename T>
T load(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap)
    std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

template <typename T>
void decodeAs(const unsigned char* data, std::size_t count, bool swap, std::int32_t* out,
              const ImageSource& src) {
  for (std::size_t i = 0; i < count; ++i) {
    const T v = load<T>(data + i * sizeof(T), swap);
    if constexpr (sizeof(T) >= 4) {
      if (static_cast<long double>(v) > std::numeric_limits<std::int32_t>::max() ||
          static_cast<long double>(v) < std::numeric_limits<std::int32_t>::min())
        imageError(src, "label " + std::to_string(v) + " at element " + std::to_string(i) +
                            " does not fit a 32-bit phase id");
    }
    out[i] = static_cast<std::int32_t>(v);
  }
}
} // namespace

void decodeLabels(const unsigned char* data, std::size_t count, ScalarType type, bool big_endian,
                  std::int32_t* out, const ImageSource& src) {
  const bool swap = big_endian != (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__);
  switch (type) {
  case ScalarType::Int8:
    return decodeAs<std::int8_t>(data, count, swap, out, src);
  case ScalarType::UInt8:
    return decodeAs<std::uint8_t>(data, count, swap, out, src);
  case ScalarType::Int16:
    return decodeAs<std::int16_t>(data, count, swap, out, src);
  case ScalarType::UInt16:
    return decodeAs<std::uint16_t>(data, count, swap, out, src);
  case ScalarType::Int32:
    return decodeAs<std::int32_t>(data, count, swap, out, src);
  case ScalarType::UInt32:
    return decodeAs<std::uint32_t>(data, count, swap, out, src);
  case ScalarType::Int64:
    return decodeAs<std::int64_t>(data, count, swap, out, src);
  case ScalarType::UInt64:
    return decodeAs<std::uint64_t>(data, count, swap, out, src);
  }
}

std::vector<std::int32_t> toXSlowest(std::vector<std::int32_t> file, const std::array<int, 3>& n,
                                     AxisOrder order) {
  if (order == AxisOrder::Xyz)
    return file;
  std::vector<std::int32_t> out(file.size());
  std::size_t at = 0;
  for (std::size_t k = 0; k < static_cast<std::size_t>(n[2]); ++k)
    for (std::size_t j = 0; j < static_cast<std::size_t>(n[1]); ++j)
      for (std::size_t i = 0; i < static_cast<std::size_t>(n[0]); ++i)
        out[xSlowest(n, i, j, k)] = file[at++];
  return out;
}

ScalarType smallestType(const VoxelImage& image) {
  std::int32_t lo = 0, hi = 0;
  for (std::int32_t v : image.value) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (lo < 0)
    return ScalarType::Int32;
  if (hi <= 255)
    return ScalarType::UInt8;
  if (hi <= 65535)
    return ScalarType::UInt16;
  return ScalarType::UInt32;
}

} // namespace detail

namespace {
/// The voxels the crop window of @p src keeps of an image of @p n voxels.
std::array<int, 3> cropWindow(const std::array<int, 3>& n, const std::array<int, 3>& start,
                              const std::array<int, 3>& count, const ImageSource& src) {
  std::array<int, 3> m{};
  for (std::size_t d = 0; d < 3; ++d) {
    m[d] = count[d] > 0 ? count[d] : n[d] - start[d];
    if (start[d] < 0 || m[d] < 1 || start[d] + m[d] > n[d])
      throw Error("crop window [" + std::to_string(start[d]) + ", " +
                      std::to_string(start[d] + m[d]) + ") along " + std::string(1, "xyz"[d]) +
                      " leaves the image (" + std::to_string(n[d]) + " voxels, " +
                      src.path.string() + ")",
                  {src.cell_file, 0, "cell.crop"});
  }
  return m;
}

/// Throws unless @p f divides every dimension of @p n.
void checkDivides(const std::array<int, 3>& n, int f, const ImageSource& src) {
  for (std::size_t d = 0; d < 3; ++d)
    if (n[d] % f != 0)
      throw Error("downsample = " + std::to_string(f) + " does not divide the " +
                      std::to_string(n[d]) + " voxels along " + std::string(1, "xyz"[d]) +
                      " (after the crop; " + src.path.string() + ")",
                  {src.cell_file, 0, "cell.downsample"});
}
} // namespace

VoxelImage cropImage(const VoxelImage& image, const std::array<int, 3>& start,
                     const std::array<int, 3>& count, const ImageSource& src) {
  const std::array<int, 3> m = cropWindow(image.n, start, count, src);
  if (m == image.n)
    return image;
  VoxelImage out;
  out.n = m;
  out.spacing = image.spacing;
  out.value.resize(out.voxels());
  for (int i = 0; i < m[0]; ++i)
    for (int j = 0; j < m[1]; ++j)
      for (int k = 0; k < m[2]; ++k)
        out.value[detail::xSlowest(m, static_cast<std::size_t>(i), static_cast<std::size_t>(j),
                                   static_cast<std::size_t>(k))] =
            image.value[detail::xSlowest(image.n, static_cast<std::size_t>(i + start[0]),
                                         static_cast<std::size_t>(j + start[1]),
                                         static_cast<std::size_t>(k + start[2]))];
  return out;
}

VoxelImage downsampleImage(const VoxelImage& image, int f, const ImageSource& src) {
  if (f == 1)
    return image;
  checkDivides(image.n, f, src);
  VoxelImage out;
  out.n = {image.n[0] / f, image.n[1] / f, image.n[2] / f};
  if (image.spacing)
    out.spacing = *image.spacing * f;
  out.value.resize(out.voxels());
  const std::size_t F = static_cast<std::size_t>(f);
  core::ParallelErrors errors; // the vote count allocates
#pragma omp parallel for schedule(static)
  for (int I = 0; I < out.n[0]; ++I)
    errors.run([&] {
      std::map<std::int32_t, int> votes;
      for (std::size_t J = 0; J < static_cast<std::size_t>(out.n[1]); ++J)
        for (std::size_t K = 0; K < static_cast<std::size_t>(out.n[2]); ++K) {
          votes.clear();
          for (std::size_t a = 0; a < F; ++a)
            for (std::size_t b = 0; b < F; ++b)
              for (std::size_t c = 0; c < F; ++c)
                ++votes[image.value[detail::xSlowest(image.n, static_cast<std::size_t>(I) * F + a,
                                                     J * F + b, K * F + c)]];
          // most votes; std::map iterates labels in increasing order, so a tie
          // keeps the smallest label
          auto best = votes.begin();
          for (auto it = votes.begin(); it != votes.end(); ++it)
            if (it->second > best->second)
              best = it;
          out.value[detail::xSlowest(out.n, static_cast<std::size_t>(I), J, K)] = best->first;
        }
    });
  errors.rethrow();
  return out;
}

namespace {
/// Refuses an image whose header gives other dimensions than the cell
/// file's `dimensions` (when it states them).
std::array<int, 3> checkDeclared(const std::array<int, 3>& n, const ImageSource& src) {
  const auto& m = src.dimensions;
  if (src.format != ImageFormat::Raw && m != std::array<int, 3>{0, 0, 0} && m != n)
    throw Error("the image " + src.path.string() + " holds " + std::to_string(n[0]) + " x " +
                    std::to_string(n[1]) + " x " + std::to_string(n[2]) + " voxels, the cell " +
                    "declares " + std::to_string(m[0]) + " x " + std::to_string(m[1]) + " x " +
                    std::to_string(m[2]) + " (truncated stack or wrong file?)",
                {src.cell_file, 0, "cell.dimensions"});
  return n;
}

VoxelImage readFormat(const ImageSource& src) {
  switch (src.format) {
  case ImageFormat::Hdf5:
    return detail::readHdf5Image(src);
  case ImageFormat::Vti:
    return detail::readVtiImage(src);
  case ImageFormat::Raw:
    return detail::readRawImage(src);
  case ImageFormat::Tiff:
    return detail::readTiffImage(src);
  }
  return {};
}

VoxelImage readWhole(const ImageSource& src) {
  VoxelImage img = readFormat(src);
  checkDeclared(img.n, src);
  return img;
}

std::array<int, 3> probeFormat(const ImageSource& src) {
  switch (src.format) {
  case ImageFormat::Hdf5:
    return detail::probeHdf5Image(src);
  case ImageFormat::Vti:
    return detail::probeVtiImage(src);
  case ImageFormat::Raw:
    detail::openImage(src); // a regular file
    return src.dimensions;
  case ImageFormat::Tiff:
    return detail::probeTiffImage(src);
  }
  return {};
}

std::array<int, 3> probeWhole(const ImageSource& src) {
  return checkDeclared(probeFormat(src), src);
}
} // namespace

VoxelImage readImage(const ImageSource& src) {
  VoxelImage img = readWhole(src);
  img = cropImage(img, src.crop_start, src.crop_count, src);
  return downsampleImage(img, src.downsample, src);
}

std::array<int, 3> imageShape(const ImageSource& src) {
  VoxelImage header;
  header.n = probeWhole(src);
  std::array<int, 3> m = cropWindow(header.n, src.crop_start, src.crop_count, src);
  checkDivides(m, src.downsample, src);
  for (int& x : m)
    x /= src.downsample;
  return m;
}

std::string writeImage(const VoxelImage& image, const std::filesystem::path& path,
                       ImageFormat format, const ImageWriteOptions& options) {
  switch (format) {
  case ImageFormat::Hdf5:
    detail::writeHdf5Image(image, path, options);
    return "image = \"" + path.filename().string() + "\"\ndataset = \"/" + options.name + "\"\n";
  case ImageFormat::Vti:
    detail::writeVtiImage(image, path, options);
    return "image = \"" + path.filename().string() + "\"\n";
  case ImageFormat::Raw: {
    const ScalarType t = detail::smallestType(image);
    detail::writeRawImage(image, path, t);
    return "image = \"" + path.filename().string() + "\"\ndimensions = [" +
           std::to_string(image.n[0]) + ", " + std::to_string(image.n[1]) + ", " +
           std::to_string(image.n[2]) + "]\ntype = \"" + toString(t) +
           "\"\nbyte_order = \"little\"\naxes = \"zyx\"\n";
  }
  case ImageFormat::Tiff:
    detail::writeTiffImage(image, path);
    return "image = \"" + path.filename().string() + "\"\n";
  }
  return {};
}

} // namespace lamina::micro
