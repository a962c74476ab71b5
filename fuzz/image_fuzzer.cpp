/// @file image_fuzzer.cpp
/// @brief libFuzzer target: the voxel-image readers (HDF5, VTI, raw, TIFF)
/// through imageShape (the header path) and readImage. The first byte picks
/// the format (its value mod 4: 0 HDF5, 1 VTI, 2 raw, 3 TIFF; bit 2 asks for
/// down-sampling by 2); a raw input then gives five bytes of the cell's keys
/// (voxels - 1 along x, y, z up to 16; type, byte order and axes; header
/// bytes) before its content. Everything after the prefix is the image file
/// (fuzz/seeds/image holds a small valid file of each format and encoding).
/// An image the header says holds more than 2^20 voxels is only probed:
/// the memory of a large read is the malformed tests' business (libFuzzer's
/// RSS limit would report it), not the parser's. HDF5 inputs take the
/// header path only (open, dataset, type, rank, dimensions): past it, the
/// HDF5 library (1.10) itself has memory errors on corrupt object headers
/// (a heap use-after-free in H5O__msg_iterate_real under H5Aexists was the
/// first thing this target found), which lamina cannot fix or check for.

#include "fuzz_input.hpp"
#include "micro/image_io.hpp"

#include <array>

namespace {

/// The source of a fuzz input: format and raw keys from the prefix, @p path
/// the scratch file; @p prefix receives the prefix length.
lamina::micro::ImageSource sourceOf(const std::uint8_t* data, std::size_t size,
                                    std::size_t& prefix) {
  using namespace lamina::micro;
  ImageSource s;
  s.cell_file = "fuzz-cell.toml";
  constexpr std::array<ImageFormat, 4> kFormats{ImageFormat::Hdf5, ImageFormat::Vti,
                                                ImageFormat::Raw, ImageFormat::Tiff};
  s.format = kFormats[data[0] % 4];
  s.downsample = data[0] & 4 ? 2 : 1;
  prefix = 1;
  if (s.format == ImageFormat::Raw && size >= 6) {
    prefix = 6;
    s.dimensions = {1 + data[1] % 16, 1 + data[2] % 16, 1 + data[3] % 16};
    s.type = static_cast<ScalarType>(data[4] % 8);
    s.big_endian = data[4] & 8;
    s.axes = data[4] & 16 ? AxisOrder::Zyx : AxisOrder::Xyz;
    s.header_bytes = data[5] % 16;
  } else if (s.format == ImageFormat::Raw) {
    s.dimensions = {1, 1, 1};
  }
  return s;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lamina::micro;
  if (size == 0)
    return 0;
  std::size_t prefix = 0;
  ImageSource src = sourceOf(data, size, prefix);
  static const char* const kNames[] = {"input.h5", "input.vti", "input.raw", "input.tif"};
  src.path = lamina::fuzz::scratchFile(kNames[data[0] % 4],
                                       lamina::fuzz::text(data + prefix, size - prefix));
  return lamina::fuzz::guarded([&] {
    const std::array<int, 3> n = imageShape(src);
    const double voxels = static_cast<double>(n[0]) * n[1] * n[2] * src.downsample *
                          src.downsample * src.downsample;
    if (voxels <= double(1 << 20) && src.format != ImageFormat::Hdf5)
      readImage(src);
  });
}
