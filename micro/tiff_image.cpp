// Multi-page TIFF stacks through libtiff: page p is the slice z = p, width x,
// height y, one integer sample per pixel (see image_formats.hpp).

#include "core/atomic_file.hpp"
#include "micro/image_formats.hpp"

#include <tiffio.h>

#include <cstring>
#include <memory>

namespace lamina::micro::detail {

namespace {

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
using TiffPtr = std::unique_ptr<TIFF, TiffCloser>;

TiffPtr openTiff(const ImageSource& src) {
  // libtiff prints warnings (unknown tags) on stderr: errors are ours to report
  TIFFSetWarningHandler(nullptr);
  TIFFSetErrorHandler(nullptr);
  TiffPtr t(TIFFOpen(src.path.c_str(), "r"));
  if (!t)
    imageError(src, "not a TIFF file (or unreadable)");
  return t;
}

/// Width, height and sample type of the current page.
struct Page {
  std::uint32_t width = 0, height = 0;
  ScalarType type = ScalarType::UInt8;
};

Page pageOf(TIFF* t, const ImageSource& src, int page) {
  Page p;
  std::uint16_t bits = 0, samples = 1, format = SAMPLEFORMAT_UINT;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &p.width);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &p.height);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &format);
  const std::string where = "page " + std::to_string(page) + ": ";
  if (samples != 1)
    imageError(src, where + std::to_string(samples) +
                        " samples per pixel; a label image has one (grey levels)");
  if (TIFFIsTiled(t))
    imageError(src, where + "tiled TIFF is not supported (write the stack in strips)");
  const bool sign = format == SAMPLEFORMAT_INT;
  if (format != SAMPLEFORMAT_UINT && format != SAMPLEFORMAT_INT)
    imageError(src, where + "samples must be integers (labels), not floating point");
  switch (bits) {
  case 8:
    p.type = sign ? ScalarType::Int8 : ScalarType::UInt8;
    break;
  case 16:
    p.type = sign ? ScalarType::Int16 : ScalarType::UInt16;
    break;
  case 32:
    p.type = sign ? ScalarType::Int32 : ScalarType::UInt32;
    break;
  default:
    imageError(src, where + std::to_string(bits) + " bits per sample; labels need 8, 16 or 32");
  }
  return p;
}

} // namespace

std::array<int, 3> probeTiffImage(const ImageSource& src) {
  TiffPtr t = openTiff(src);
  const Page p = pageOf(t.get(), src, 0);
  return {static_cast<int>(p.width), static_cast<int>(p.height),
          static_cast<int>(TIFFNumberOfDirectories(t.get()))};
}

VoxelImage readTiffImage(const ImageSource& src) {
  TiffPtr t = openTiff(src);
  const Page first = pageOf(t.get(), src, 0);
  VoxelImage img;
  img.n = {static_cast<int>(first.width), static_cast<int>(first.height),
           static_cast<int>(TIFFNumberOfDirectories(t.get()))};
  checkImageMemory(src, img.voxels(), 4);
  img.value.resize(img.voxels());
  std::vector<unsigned char> line;
  std::vector<std::int32_t> row(first.width);
  for (int z = 0; z < img.n[2]; ++z) {
    if (!TIFFSetDirectory(t.get(), static_cast<tdir_t>(z)))
      imageError(src, "cannot read page " + std::to_string(z) + " (truncated stack?)");
    const Page p = pageOf(t.get(), src, z);
    if (p.width != first.width || p.height != first.height || p.type != first.type)
      imageError(src, "page " + std::to_string(z) + " is " + std::to_string(p.width) + " x " +
                          std::to_string(p.height) + " " + toString(p.type) + ", page 0 is " +
                          std::to_string(first.width) + " x " + std::to_string(first.height) + " " +
                          toString(first.type) + ": a stack needs equal pages");
    line.resize(static_cast<std::size_t>(TIFFScanlineSize(t.get())));
    for (std::uint32_t y = 0; y < p.height; ++y) {
      if (TIFFReadScanline(t.get(), line.data(), y, 0) < 0)
        imageError(src, "cannot read row " + std::to_string(y) + " of page " + std::to_string(z) +
                            " (truncated or corrupt file)");
      // libtiff returns native byte order
      decodeLabels(line.data(), p.width, p.type, __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__, row.data(),
                   src);
      for (std::uint32_t x = 0; x < p.width; ++x)
        img.value[xSlowest(img.n, x, y, static_cast<std::size_t>(z))] = row[x];
    }
  }
  return img;
}

void writeTiffImage(const VoxelImage& image, const std::filesystem::path& path) {
  const ScalarType type = smallestType(image);
  const int bytes = bytesOf(type);
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    TiffPtr t(TIFFOpen(tmp.c_str(), "w"));
    if (!t)
      throw Error("cannot create TIFF file", {tmp.string(), 0, ""});
    std::vector<unsigned char> line(static_cast<std::size_t>(image.n[0] * bytes));
    for (int z = 0; z < image.n[2]; ++z) {
      TIFFSetField(t.get(), TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(image.n[0]));
      TIFFSetField(t.get(), TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(image.n[1]));
      TIFFSetField(t.get(), TIFFTAG_BITSPERSAMPLE, static_cast<std::uint16_t>(8 * bytes));
      TIFFSetField(t.get(), TIFFTAG_SAMPLESPERPIXEL, static_cast<std::uint16_t>(1));
      TIFFSetField(t.get(), TIFFTAG_SAMPLEFORMAT,
                   static_cast<std::uint16_t>(type == ScalarType::Int32 ? SAMPLEFORMAT_INT
                                                                        : SAMPLEFORMAT_UINT));
      TIFFSetField(t.get(), TIFFTAG_PHOTOMETRIC,
                   static_cast<std::uint16_t>(PHOTOMETRIC_MINISBLACK));
      TIFFSetField(t.get(), TIFFTAG_PLANARCONFIG, static_cast<std::uint16_t>(PLANARCONFIG_CONTIG));
      TIFFSetField(t.get(), TIFFTAG_COMPRESSION, static_cast<std::uint16_t>(COMPRESSION_NONE));
      TIFFSetField(t.get(), TIFFTAG_ROWSPERSTRIP, static_cast<std::uint32_t>(image.n[1]));
      TIFFSetField(t.get(), TIFFTAG_SUBFILETYPE, static_cast<std::uint32_t>(FILETYPE_PAGE));
      TIFFSetField(t.get(), TIFFTAG_PAGENUMBER, static_cast<std::uint16_t>(z),
                   static_cast<std::uint16_t>(image.n[2]));
      for (int y = 0; y < image.n[1]; ++y) {
        for (int x = 0; x < image.n[0]; ++x) {
          const std::int32_t v =
              image.value[xSlowest(image.n, static_cast<std::size_t>(x),
                                   static_cast<std::size_t>(y), static_cast<std::size_t>(z))];
          // native byte order, as libtiff expects
          if (bytes == 1) {
            line[static_cast<std::size_t>(x)] = static_cast<unsigned char>(v);
          } else if (bytes == 2) {
            const std::uint16_t s = static_cast<std::uint16_t>(v);
            std::memcpy(&line[static_cast<std::size_t>(2 * x)], &s, 2);
          } else {
            std::memcpy(&line[static_cast<std::size_t>(4 * x)], &v, 4);
          }
        }
        if (TIFFWriteScanline(t.get(), line.data(), static_cast<std::uint32_t>(y), 0) < 0)
          throw Error("cannot write TIFF row", {tmp.string(), 0, ""});
      }
      if (!TIFFWriteDirectory(t.get()))
        throw Error("cannot write TIFF page", {tmp.string(), 0, ""});
    }
  }
  core::renameIntoPlace(tmp, path);
}

} // namespace lamina::micro::detail
