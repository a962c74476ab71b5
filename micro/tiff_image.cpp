// Multi-page TIFF stacks through libtiff: page p is the slice z = p, width x,
// height y, one integer sample per pixel (see image_formats.hpp).

#include "core/atomic_file.hpp"
#include "micro/image_formats.hpp"

#include <tiffio.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace lamina::micro::detail {

namespace {

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
using TiffPtr = std::unique_ptr<TIFF, TiffCloser>;

/// An open TIFF stack and the size of its file.
struct OpenTiff {
  TiffPtr tiff;
  std::uint64_t bytes = 0;
};

OpenTiff openTiff(const ImageSource& src) {
  // libtiff prints warnings (unknown tags) on stderr: errors are ours to report
  TIFFSetWarningHandler(nullptr);
  TIFFSetErrorHandler(nullptr);
  const core::InputFile in = openImage(src);
  // libtiff reads the descriptor checked above (it closes its own copy)
  const int fd = ::dup(in.fd());
  OpenTiff t{TiffPtr(fd < 0 ? nullptr : TIFFFdOpen(fd, src.path.c_str(), "r")), in.size()};
  if (!t.tiff) {
    if (fd >= 0)
      ::close(fd);
    imageError(src, "not a TIFF file (or unreadable)");
  }
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


/// Checks that every strip of the current page (@p page) lies within the
/// file's @p bytes and, uncompressed, holds the rows it stands for.
void checkStrips(TIFF* t, const ImageSource& src, int page, std::uint64_t bytes) {
  const std::string where = "truncated TIFF stack: page " + std::to_string(page) + ", strip ";
  std::uint16_t compression = COMPRESSION_NONE;
  std::uint32_t height = 0, rows_per_strip = 0;
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &height);
  TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &rows_per_strip);
  rows_per_strip = std::max<std::uint32_t>(1, std::min(rows_per_strip, height));
  const std::uint64_t row = TIFFScanlineSize64(t);
  const std::uint32_t strips = TIFFNumberOfStrips(t);
  if (height > 0 && strips < (height - 1) / rows_per_strip + 1)
    imageError(src, where + "table lists " + std::to_string(strips) + " strips for " +
                        std::to_string(height) + " rows");
  for (std::uint32_t s = 0; s < strips; ++s) {
    const std::uint64_t at = TIFFGetStrileOffset(t, s), n = TIFFGetStrileByteCount(t, s);
    if (at > bytes || n > bytes - at)
      imageError(src, where + std::to_string(s) + " (bytes " + std::to_string(at) + " + " +
                          std::to_string(n) + ") lies beyond the end of the file (" +
                          std::to_string(bytes) + " bytes)");
    const std::uint64_t rows =
        std::min<std::uint64_t>(rows_per_strip, height - std::min<std::uint64_t>(
                                                             height, std::uint64_t{s} * rows_per_strip));
    if (compression == COMPRESSION_NONE && n < rows * row)
      imageError(src, where + std::to_string(s) + " holds " + std::to_string(n) +
                          " bytes, its rows need " + std::to_string(rows * row));
  }
}

/// The pages a stack declares on page 0 (PageNumber tag, or ImageJ's
/// "images=N" description); 0 when it declares none. PageNumber's total is a
/// 16-bit field: a stack of 65,536 pages or more cannot state its count there
/// (lamina's writer leaves it out), so such a total is taken as unknown.
std::uint64_t declaredPages(TIFF* t, std::uint64_t count) {
  std::uint16_t page = 0, total = 0;
  if (TIFFGetField(t, TIFFTAG_PAGENUMBER, &page, &total) == 1 && total > 0)
    return count > 0xffff ? 0 : total;
  char* text = nullptr;
  if (TIFFGetField(t, TIFFTAG_IMAGEDESCRIPTION, &text) == 1 && text &&
      std::strncmp(text, "ImageJ=", 7) == 0)
    if (const char* at = std::strstr(text, "\nimages="))
      return std::strtoull(at + 8, nullptr, 10);
  return 0;
}

/// What a scan of the whole stack found: page 0's shape and the page count.
struct Stack {
  Page first;
  int pages = 0;
};

/// Walks every page of the stack: equal pages, strips within the file, the
/// directory chain complete and the page count as page 0 declares it.
Stack scanStack(TIFF* t, const ImageSource& src, std::uint64_t bytes) {
  Stack s;
  s.first = pageOf(t, src, 0);
  const tdir_t count = TIFFNumberOfDirectories(t);
  const std::uint64_t declared = declaredPages(t, count);
  if (count > 1000000)
    imageError(src, std::to_string(count) + " pages; at most 1000000 are read");
  for (tdir_t z = 0; z < count; ++z) {
    if (!TIFFSetDirectory(t, z))
      imageError(src, "truncated TIFF stack: cannot read page " + std::to_string(z));
    const Page p = pageOf(t, src, static_cast<int>(z));
    if (p.width != s.first.width || p.height != s.first.height || p.type != s.first.type)
      imageError(src, "page " + std::to_string(z) + " is " + std::to_string(p.width) + " x " +
                          std::to_string(p.height) + " " + toString(p.type) + ", page 0 is " +
                          std::to_string(s.first.width) + " x " + std::to_string(s.first.height) +
                          " " + toString(s.first.type) + ": a stack needs equal pages");
    checkStrips(t, src, static_cast<int>(z), bytes);
  }
  if (!TIFFLastDirectory(t))
    imageError(src, "truncated TIFF stack: page " + std::to_string(count - 1) +
                        " points to a next page that the file (" + std::to_string(bytes) +
                        " bytes) does not hold");
  if (declared > 0 && declared != count)
    imageError(src, "truncated TIFF stack: page 0 declares " + std::to_string(declared) +
                        " pages, the file holds " + std::to_string(count));
  s.pages = static_cast<int>(count);
  return s;
}

} // namespace

std::array<int, 3> probeTiffImage(const ImageSource& src) {
  const OpenTiff t = openTiff(src);
  const Stack s = scanStack(t.tiff.get(), src, t.bytes);
  return {static_cast<int>(s.first.width), static_cast<int>(s.first.height), s.pages};
}

VoxelImage readTiffImage(const ImageSource& src) {
  const OpenTiff t = openTiff(src);
  const Stack s = scanStack(t.tiff.get(), src, t.bytes);
  VoxelImage img;
  img.n = {static_cast<int>(s.first.width), static_cast<int>(s.first.height), s.pages};
  checkImageMemory(src, img.voxels(), 4);
  img.value.resize(img.voxels());
  std::vector<unsigned char> line;
  std::vector<std::int32_t> row(s.first.width);
  for (int z = 0; z < img.n[2]; ++z) {
    if (!TIFFSetDirectory(t.tiff.get(), static_cast<tdir_t>(z)))
      imageError(src, "truncated TIFF stack: cannot read page " + std::to_string(z));
    line.resize(static_cast<std::size_t>(TIFFScanlineSize64(t.tiff.get())));
    for (std::uint32_t y = 0; y < s.first.height; ++y) {
      if (TIFFReadScanline(t.tiff.get(), line.data(), y, 0) < 0)
        imageError(src, "cannot read row " + std::to_string(y) + " of page " + std::to_string(z) +
                            " (truncated or corrupt file)");
      // libtiff returns native byte order
      decodeLabels(line.data(), s.first.width, s.first.type,
                   __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__, row.data(), src);
      for (std::uint32_t x = 0; x < s.first.width; ++x)
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
      if (image.n[2] <= 0xffff) // PageNumber is 16-bit: no count rather than a wrapped one
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
