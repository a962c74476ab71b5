// VTK XML ImageData (.vti) through expat (XML), zlib (compressed blocks) and
// OpenSSL's base64 codec. Layout facts from the VTK file-format
// documentation ("VTK File Formats", XML formats): binary data is a header of
// header_type integers followed by the data; uncompressed: [byte count];
// zlib: [blocks, block size, last block size, compressed size of each block]
// then the compressed blocks. Appended data starts after the '_' of the
// AppendedData element; a DataArray's offset counts from there. VTK stores
// x fastest.

#include "core/atomic_file.hpp"
#include "core/format.hpp"
#include "micro/image_formats.hpp"

#include <expat.h>
#include <openssl/evp.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <sstream>

namespace lamina::micro::detail {

namespace {

struct VtiArray {
  std::string name, type, format;
  std::uint64_t offset = 0;
  int components = 1;
  bool cell = true; // CellData (else PointData)
  std::string text; // inline content
};

/// What the XML part of a .vti file says.
struct VtiDoc {
  std::string file_type, byte_order = "LittleEndian", header_type = "UInt32", compressor;
  std::array<long, 6> extent{0, 0, 0, 0, 0, 0};
  bool have_extent = false;
  Eigen::Vector3d spacing = Eigen::Vector3d::Ones();
  bool have_spacing = false;
  int pieces = 0;
  std::vector<VtiArray> arrays;
  std::string appended_encoding;
  // parser state
  std::vector<std::string> stack;
  int current = -1;
  std::string error;
};

/// @return the decimal integer @p v (digits only, no sign, no trailing text)
/// when it is at most @p max; else records in @p d which attribute of which
/// array is not one (strtoull took "-5" as 2^64 - 5 and "x" as 0, atoi
/// "4294967297" as 1) and @return 0
std::uint64_t strictCount(VtiDoc& d, const char* v, const char* key, const std::string& array,
                          std::uint64_t max) {
  errno = 0;
  char* end = nullptr;
  const unsigned long long x = std::strtoull(v, &end, 10);
  if (v[0] < '0' || v[0] > '9' || *end != '\0' || errno == ERANGE || x > max) {
    if (d.error.empty())
      d.error = "array '" + array + "': " + key + " = '" + v + "' is not an integer from 0 to " +
                std::to_string(max);
    return 0;
  }
  return x;
}

const char* attr(const XML_Char** a, const char* name) {
  for (int i = 0; a[i]; i += 2)
    if (std::strcmp(a[i], name) == 0)
      return a[i + 1];
  return nullptr;
}

void XMLCALL onStart(void* data, const XML_Char* name, const XML_Char** a) {
  auto& d = *static_cast<VtiDoc*>(data);
  const std::string n = name;
  const std::string parent = d.stack.empty() ? "" : d.stack.back();
  d.stack.push_back(n);
  if (n == "VTKFile") {
    if (const char* v = attr(a, "type"))
      d.file_type = v;
    if (const char* v = attr(a, "byte_order"))
      d.byte_order = v;
    if (const char* v = attr(a, "header_type"))
      d.header_type = v;
    if (const char* v = attr(a, "compressor"))
      d.compressor = v;
  } else if (n == "ImageData") {
    if (const char* v = attr(a, "WholeExtent")) {
      std::istringstream is(v);
      for (long& e : d.extent)
        is >> e;
      d.have_extent = !is.fail();
    }
    if (const char* v = attr(a, "Spacing")) {
      std::istringstream is(v);
      is >> d.spacing[0] >> d.spacing[1] >> d.spacing[2];
      d.have_spacing = !is.fail();
    }
  } else if (n == "Piece") {
    ++d.pieces;
  } else if (n == "DataArray" && (parent == "CellData" || parent == "PointData")) {
    VtiArray arr;
    arr.cell = parent == "CellData";
    if (const char* v = attr(a, "Name"))
      arr.name = v;
    if (const char* v = attr(a, "type"))
      arr.type = v;
    arr.format = attr(a, "format") ? attr(a, "format") : "ascii";
    if (const char* v = attr(a, "offset"))
      arr.offset = strictCount(d, v, "offset", arr.name, std::uint64_t{1} << 62);
    if (const char* v = attr(a, "NumberOfComponents"))
      arr.components = static_cast<int>(strictCount(d, v, "NumberOfComponents", arr.name, 1 << 20));
    d.arrays.push_back(arr);
    d.current = static_cast<int>(d.arrays.size()) - 1;
  } else if (n == "AppendedData") {
    d.appended_encoding = attr(a, "encoding") ? attr(a, "encoding") : "base64";
  }
}

void XMLCALL onEnd(void* data, const XML_Char*) {
  auto& d = *static_cast<VtiDoc*>(data);
  if (!d.stack.empty() && d.stack.back() == "DataArray")
    d.current = -1;
  if (!d.stack.empty())
    d.stack.pop_back();
}

void XMLCALL onText(void* data, const XML_Char* s, int len) {
  auto& d = *static_cast<VtiDoc*>(data);
  if (d.current >= 0)
    d.arrays[static_cast<std::size_t>(d.current)].text.append(s, static_cast<std::size_t>(len));
}

struct Parsed {
  VtiDoc doc;
  std::string content;                      // the whole file
  std::size_t appended = std::string::npos; // first byte after '_'
  std::size_t appended_end = std::string::npos;
};

Parsed parse(const ImageSource& src) {
  Parsed p;
  p.content = openImage(src).readAll();
  // The appended section holds raw bytes that are not XML: parse only up to
  // the end of its start tag.
  std::size_t xml_end = p.content.size();
  const std::size_t tag = p.content.find("<AppendedData");
  if (tag != std::string::npos) {
    const std::size_t gt = p.content.find('>', tag);
    const std::size_t us = gt == std::string::npos ? gt : p.content.find('_', gt);
    if (us == std::string::npos)
      imageError(src, "truncated .vti file: AppendedData without its '_' marker");
    xml_end = gt + 1;
    p.appended = us + 1;
    p.appended_end = p.content.rfind("</AppendedData>");
    if (p.appended_end == std::string::npos || p.appended_end < p.appended)
      p.appended_end = p.content.size();
  }
  std::unique_ptr<XML_ParserStruct, void (*)(XML_Parser)> parser(XML_ParserCreate(nullptr),
                                                                 XML_ParserFree);
  XML_SetUserData(parser.get(), &p.doc);
  XML_SetElementHandler(parser.get(), onStart, onEnd);
  XML_SetCharacterDataHandler(parser.get(), onText);
  const bool final_chunk = tag == std::string::npos;
  if (XML_Parse(parser.get(), p.content.data(), static_cast<int>(xml_end), final_chunk) ==
      XML_STATUS_ERROR)
    imageError(
        src,
        std::string("XML error at line ") + std::to_string(XML_GetCurrentLineNumber(parser.get())) +
            ": " + XML_ErrorString(XML_GetErrorCode(parser.get())) +
            (XML_GetErrorCode(parser.get()) == XML_ERROR_NO_ELEMENTS ? " (truncated file?)" : ""));
  const VtiDoc& d = p.doc;
  if (!d.error.empty())
    imageError(src, d.error);
  if (d.file_type != "ImageData")
    imageError(src, "VTKFile type is '" + d.file_type + "'; a voxel image needs ImageData");
  if (!d.have_extent)
    imageError(src, "ImageData has no valid WholeExtent");
  if (d.pieces > 1)
    imageError(src, "ImageData with " + std::to_string(d.pieces) +
                        " pieces is not supported (write one piece)");
  if (d.byte_order != "LittleEndian" && d.byte_order != "BigEndian")
    imageError(src, "byte_order '" + d.byte_order + "' (LittleEndian or BigEndian)");
  if (d.header_type != "UInt32" && d.header_type != "UInt64")
    imageError(src, "header_type '" + d.header_type + "' (UInt32 or UInt64)");
  if (!d.compressor.empty() && d.compressor != "vtkZLibDataCompressor")
    imageError(src, "compressor '" + d.compressor + "' is not supported (vtkZLibDataCompressor)");
  return p;
}

const VtiArray& pickArray(const VtiDoc& d, const ImageSource& src) {
  std::string names;
  for (const auto& a : d.arrays)
    names += (names.empty() ? "" : ", ") + a.name + (a.cell ? " (CellData)" : " (PointData)");
  if (!src.dataset.empty()) {
    for (const auto& a : d.arrays)
      if (a.name == src.dataset)
        return a;
    throw Error("no array named '" + src.dataset + "' in " + src.path.string() +
                    " (it holds: " + (names.empty() ? "no arrays" : names) + ")",
                {src.cell_file, 0, "cell.dataset"});
  }
  for (const auto& a : d.arrays)
    if (a.cell)
      return a;
  if (d.arrays.empty())
    imageError(src, "no CellData or PointData array");
  return d.arrays.front();
}

/// The voxels along x, y, z of @p a; an extent that gives none, or more
/// than an int counts, is an error.
std::array<int, 3> dimsOf(const VtiDoc& d, const VtiArray& a, const ImageSource& src) {
  std::array<int, 3> n{};
  for (std::size_t i = 0; i < 3; ++i) {
    // in long double: extents near the limits of long overflow a difference
    const long double m = static_cast<long double>(d.extent[2 * i + 1]) -
                          static_cast<long double>(d.extent[2 * i]) + (a.cell ? 0 : 1);
    if (m < 1 || m > 1e9)
      imageError(src, "WholeExtent gives " + std::to_string(static_cast<double>(m)) +
                          " voxels along " + std::string(1, "xyz"[i]) + " (1 to 1e9 accepted)");
    n[i] = static_cast<int>(m);
  }
  return n;
}

/// Base64 decoding that accepts padding between blocks: VTK encodes a
/// compressed array's header and its data as separate base64 streams.
std::vector<unsigned char> base64Decode(const char* s, std::size_t len, const ImageSource& src) {
  std::string clean;
  clean.reserve(len);
  for (std::size_t i = 0; i < len; ++i)
    if (!std::isspace(static_cast<unsigned char>(s[i])))
      clean.push_back(s[i]);
  std::vector<unsigned char> out(clean.size() / 4 * 3 + 3);
  std::size_t written = 0, seg = 0;
  for (std::size_t q = 0; q + 4 <= clean.size(); q += 4) {
    const int pad = (clean[q + 3] == '=') + (clean[q + 2] == '=');
    if (pad == 0 && q + 4 < clean.size())
      continue;
    const int n =
        EVP_DecodeBlock(&out[written], reinterpret_cast<const unsigned char*>(&clean[seg]),
                        static_cast<int>(q + 4 - seg));
    if (n < 0)
      imageError(src, "invalid base64 data");
    written += static_cast<std::size_t>(n - pad);
    seg = q + 4;
  }
  if (clean.size() % 4 != 0)
    imageError(src, "truncated base64 data (length not a multiple of 4)");
  out.resize(written);
  return out;
}

std::uint64_t readHeader(const unsigned char* p, const VtiDoc& d) {
  const bool big = d.byte_order == "BigEndian";
  const std::size_t hs = d.header_type == "UInt64" ? 8 : 4;
  std::uint64_t v = 0;
  for (std::size_t b = 0; b < hs; ++b)
    v |= static_cast<std::uint64_t>(p[big ? b : hs - 1 - b]) << (8 * (hs - 1 - b));
  return v;
}

/// The array's bytes (after the header, decompressed) from @p bytes; a zlib
/// header whose sizes do not add up to @p expect bytes is refused.
std::vector<unsigned char> unpack(const unsigned char* bytes, std::size_t avail,
                                  std::uint64_t expect, const VtiDoc& d, const ImageSource& src) {
  const std::size_t hs = d.header_type == "UInt64" ? 8 : 4;
  auto truncated = [&](std::uint64_t need) {
    imageError(src, "truncated .vti file: the array needs " + std::to_string(need) +
                        " bytes, only " + std::to_string(avail) + " remain");
  };
  if (avail < hs)
    truncated(hs);
  if (d.compressor.empty()) {
    const std::uint64_t n = readHeader(bytes, d);
    if (n > avail - hs) // not hs + n: a 64-bit count would wrap
      truncated(n < UINT64_MAX - hs ? hs + n : UINT64_MAX);
    return {bytes + hs, bytes + hs + n};
  }
  if (avail < 3 * hs)
    truncated(3 * hs);
  const std::uint64_t blocks = readHeader(bytes, d), bs = readHeader(bytes + hs, d);
  std::uint64_t last = readHeader(bytes + 2 * hs, d);
  if (last == 0)
    last = bs;
  if (blocks > avail / hs)
    truncated(static_cast<std::uint64_t>(std::min<long double>((3.0L + blocks) * hs, 1e19L)));
  const std::size_t head = (3 + blocks) * hs;
  if (avail < head)
    truncated(head);
  // the header's uncompressed size against the extent, before allocating it
  const long double total = blocks == 0 ? 0.0L : (blocks - 1.0L) * bs + last;
  if (total != static_cast<long double>(expect))
    imageError(src, "size mismatch: the zlib header gives " +
                        std::to_string(static_cast<double>(total)) + " bytes, the extent needs " +
                        std::to_string(expect));
  std::vector<unsigned char> out(blocks == 0 ? 0 : (blocks - 1) * bs + last);
  std::size_t at = head, to = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t cs = readHeader(bytes + (3 + b) * hs, d);
    if (cs > avail - at)
      truncated(cs < UINT64_MAX - at ? at + cs : UINT64_MAX);
    uLongf len = static_cast<uLongf>(b + 1 == blocks ? last : bs);
    if (uncompress(&out[to], &len, bytes + at, static_cast<uLong>(cs)) != Z_OK ||
        len != (b + 1 == blocks ? last : bs))
      imageError(src, "zlib block " + std::to_string(b) + " does not decompress (corrupt file)");
    at += cs;
    to += len;
  }
  return out;
}

/// The integer types of a DataArray's `type` (VTK's names; Char and UChar are
/// older names of Int8 and UInt8).
constexpr auto kVtkTypeNames = core::enumNames<ScalarType>({{"Int8", ScalarType::Int8},
                                                            {"UInt8", ScalarType::UInt8},
                                                            {"Int16", ScalarType::Int16},
                                                            {"UInt16", ScalarType::UInt16},
                                                            {"Int32", ScalarType::Int32},
                                                            {"UInt32", ScalarType::UInt32},
                                                            {"Int64", ScalarType::Int64},
                                                            {"UInt64", ScalarType::UInt64},
                                                            {"Char", ScalarType::Int8},
                                                            {"UChar", ScalarType::UInt8}});

/// @return the bytes of one element of @p a (an integer or float type)
std::size_t elementBytes(const VtiArray& a, const ImageSource& src) {
  if (a.type == "Float32" || a.type == "Float64")
    return a.type == "Float32" ? 4 : 8;
  const std::optional<ScalarType> t = kVtkTypeNames.parse(a.type);
  if (!t)
    imageError(src,
               "array '" + a.name + "' has type '" + a.type + "'; labels need an integer type");
  return static_cast<std::size_t>(bytesOf(*t));
}

/// Decodes binary elements of VTK type @p vtk (integer or integral float).
void decodeVtk(const std::vector<unsigned char>& bytes, std::size_t count, const VtiArray& a,
               const VtiDoc& d, std::int32_t* out, const ImageSource& src) {
  const bool big = d.byte_order == "BigEndian";
  const std::size_t es = elementBytes(a, src);
  const bool is_float = a.type == "Float32" || a.type == "Float64";
  const ScalarType t = is_float ? ScalarType::UInt8 : kVtkTypeNames.parse(a.type).value();
  if (bytes.size() < count * es)
    imageError(src, "truncated .vti file: array '" + a.name + "' holds " +
                        std::to_string(bytes.size() / es) + " values, the extent needs " +
                        std::to_string(count));
  if (bytes.size() > count * es)
    imageError(src, "size mismatch: array '" + a.name + "' holds " +
                        std::to_string(bytes.size() / es) + " values, the extent needs " +
                        std::to_string(count));
  if (!is_float)
    return decodeLabels(bytes.data(), count, t, big, out, src);
  const bool swap = big != (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__);
  for (std::size_t i = 0; i < count; ++i) {
    unsigned char b[8];
    std::memcpy(b, &bytes[i * es], es);
    if (swap)
      std::reverse(b, b + es);
    double v;
    if (es == 4) {
      float f;
      std::memcpy(&f, b, 4);
      v = f;
    } else {
      std::memcpy(&v, b, 8);
    }
    if (v != std::floor(v) || std::abs(v) > 2147483647.0)
      imageError(src, "array '" + a.name + "' value " + core::formatShort(v) + " at element " +
                          std::to_string(i) + " is not an integer label");
    out[i] = static_cast<std::int32_t>(v);
  }
}

} // namespace

std::array<int, 3> probeVtiImage(const ImageSource& src) {
  const Parsed p = parse(src);
  return dimsOf(p.doc, pickArray(p.doc, src), src);
}

VoxelImage readVtiImage(const ImageSource& src) {
  const Parsed p = parse(src);
  const VtiDoc& d = p.doc;
  const VtiArray& a = pickArray(d, src);
  VoxelImage img;
  img.n = dimsOf(d, a, src);
  if (a.components != 1)
    imageError(src, "array '" + a.name + "' has " + std::to_string(a.components) +
                        " components; labels have one");
  if (d.have_spacing)
    img.spacing = d.spacing;
  const std::size_t count = img.voxels();
  checkImageMemory(src, count, 8);
  std::vector<std::int32_t> file(count);
  if (a.format == "ascii") {
    std::istringstream is(a.text);
    double v;
    std::size_t i = 0;
    while (is >> v) {
      if (i == count)
        imageError(src, "size mismatch: array '" + a.name + "' holds more than the " +
                            std::to_string(count) + " values of its extent");
      if (v != std::floor(v))
        imageError(src, "array '" + a.name + "' value " + core::formatShort(v) +
                            " is not an integer label");
      file[i++] = static_cast<std::int32_t>(v);
    }
    if (!is.eof())
      imageError(src, "array '" + a.name + "': a value is not a number");
    if (i < count)
      imageError(src, "truncated .vti file: array '" + a.name + "' holds " + std::to_string(i) +
                          " values, its extent needs " + std::to_string(count));
  } else {
    std::vector<unsigned char> bytes;
    if (a.format == "binary") {
      bytes = base64Decode(a.text.data(), a.text.size(), src);
    } else if (a.format == "appended") {
      if (p.appended == std::string::npos)
        imageError(src, "array '" + a.name + "' is appended but the file has no AppendedData");
      if (a.offset > p.appended_end - p.appended) // compared, not added: no wrap-around
        imageError(src, "truncated .vti file: array '" + a.name + "' starts at offset " +
                            std::to_string(a.offset) + " beyond the appended data");
      const std::size_t at = p.appended + a.offset;
      if (at > p.appended_end)
        imageError(src, "truncated .vti file: array '" + a.name + "' starts at offset " +
                            std::to_string(a.offset) + " beyond the appended data");
      if (d.appended_encoding == "raw")
        bytes.assign(p.content.begin() + static_cast<std::ptrdiff_t>(at),
                     p.content.begin() + static_cast<std::ptrdiff_t>(p.appended_end));
      else
        bytes = base64Decode(p.content.data() + at, p.appended_end - at, src);
    } else {
      imageError(src, "array '" + a.name + "' has format '" + a.format +
                          "' (ascii, binary or appended)");
    }
    const std::vector<unsigned char> data =
        unpack(bytes.data(), bytes.size(), count * elementBytes(a, src), d, src);
    decodeVtk(data, count, a, d, file.data(), src);
  }
  img.value = toXSlowest(std::move(file), img.n, AxisOrder::Zyx); // VTK: x fastest
  return img;
}

namespace {

void putU64(std::string& s, std::uint64_t v) {
  for (int b = 0; b < 8; ++b, v >>= 8)
    s.push_back(static_cast<char>(v & 0xff));
}

std::string base64Encode(const std::string& bytes) {
  std::string out(4 * ((bytes.size() + 2) / 3) + 1, '\0');
  const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                reinterpret_cast<const unsigned char*>(bytes.data()),
                                static_cast<int>(bytes.size()));
  out.resize(static_cast<std::size_t>(n));
  return out;
}

/// Header and data of the array: [count][data], or zlib blocks. For inline
/// binary the two parts are base64-encoded separately when compressed (as
/// VTK writes them).
std::pair<std::string, std::string> payload(const std::string& data, bool zlib) {
  std::string head, body;
  if (!zlib) {
    putU64(head, data.size());
    return {head, data};
  }
  const std::size_t bs = 1 << 15;
  const std::size_t blocks = (data.size() + bs - 1) / bs;
  putU64(head, blocks);
  putU64(head, bs);
  putU64(head, blocks == 0 ? 0 : data.size() - (blocks - 1) * bs);
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t len = std::min(bs, data.size() - b * bs);
    uLongf clen = compressBound(static_cast<uLong>(len));
    std::string c(clen, '\0');
    compress2(reinterpret_cast<Bytef*>(c.data()), &clen,
              reinterpret_cast<const Bytef*>(data.data() + b * bs), static_cast<uLong>(len),
              Z_DEFAULT_COMPRESSION);
    c.resize(clen);
    putU64(head, clen);
    body += c;
  }
  return {head, body};
}

} // namespace

void writeVtiImage(const VoxelImage& image, const std::filesystem::path& path,
                   const ImageWriteOptions& options) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
                "the writer assumes a little-endian host");
  std::string data;
  data.reserve(image.voxels() * 4);
  for (std::size_t k = 0; k < static_cast<std::size_t>(image.n[2]); ++k)
    for (std::size_t j = 0; j < static_cast<std::size_t>(image.n[1]); ++j)
      for (std::size_t i = 0; i < static_cast<std::size_t>(image.n[0]); ++i) {
        const std::int32_t v = image.value[xSlowest(image.n, i, j, k)];
        data.append(reinterpret_cast<const char*>(&v), 4);
      }
  const Eigen::Vector3d h = image.spacing.value_or(Eigen::Vector3d::Ones());
  const bool zlib = options.zlib && options.vti != VtiEncoding::Ascii;
  std::ostringstream x;
  const std::string extent = "0 " + std::to_string(image.n[0]) + " 0 " +
                             std::to_string(image.n[1]) + " 0 " + std::to_string(image.n[2]);
  x << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
       "byte_order=\"LittleEndian\" header_type=\"UInt64\""
    << (zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n  <ImageData WholeExtent=\""
    << extent << "\" Origin=\"0 0 0\" Spacing=\"" << core::formatExact(h[0]) << " "
    << core::formatExact(h[1]) << " " << core::formatExact(h[2]) << "\">\n    <Piece Extent=\""
    << extent << "\">\n      <CellData Scalars=\"" << options.name
    << "\">\n        <DataArray type=\"Int32\" Name=\"" << options.name << "\" format=\"";
  std::string appended;
  switch (options.vti) {
  case VtiEncoding::Ascii: {
    x << "ascii\">\n";
    std::size_t at = 0;
    for (std::size_t i = 0; i < data.size(); i += 4, ++at) {
      std::int32_t v;
      std::memcpy(&v, &data[i], 4);
      x << (at % 20 == 0 ? (at ? "\n" : "") : " ") << v;
    }
    x << "\n        </DataArray>\n";
    break;
  }
  case VtiEncoding::Binary: {
    const auto [head, body] = payload(data, zlib);
    x << "binary\">\n"
      << (zlib ? base64Encode(head) + base64Encode(body) : base64Encode(head + body))
      << "\n        </DataArray>\n";
    break;
  }
  case VtiEncoding::Appended: {
    const auto [head, body] = payload(data, zlib);
    x << "appended\" offset=\"0\"/>\n";
    appended = head + body;
    break;
  }
  }
  x << "      </CellData>\n    </Piece>\n  </ImageData>\n";
  if (options.vti == VtiEncoding::Appended)
    x << "  <AppendedData encoding=\"raw\">\n   _" << appended << "\n  </AppendedData>\n";
  x << "</VTKFile>\n";
  core::writeFileAtomically(path, x.str());
}

} // namespace lamina::micro::detail
