// Raw voxel images: a headerless array whose dimensions, element type, byte
// order and axis order the cell file gives (see image_formats.hpp).

#include "core/atomic_file.hpp"
#include "micro/image_formats.hpp"

#include <cstring>

namespace lamina::micro::detail {

VoxelImage readRawImage(const ImageSource& src) {
  const core::InputFile in = openImage(src);
  VoxelImage img;
  img.n = src.dimensions;
  const std::size_t bytes = static_cast<std::size_t>(bytesOf(src.type));
  const std::uint64_t have = in.size();
  // in double first: dimensions up to 1e9 each overflow 64 bits
  const double need_d = static_cast<double>(src.header_bytes) +
                        static_cast<double>(img.n[0]) * img.n[1] * img.n[2] * bytes;
  const std::string what = std::to_string(img.n[0]) + " x " + std::to_string(img.n[1]) + " x " +
                           std::to_string(img.n[2]) + " " + toString(src.type) + " voxels after " +
                           std::to_string(src.header_bytes) + " header bytes";
  if (need_d > static_cast<double>(have))
    imageError(src, "truncated raw file: " + what + " need " +
                        (need_d < 1e18 ? std::to_string(static_cast<std::uint64_t>(need_d))
                                       : std::to_string(need_d)) +
                        " bytes, the file has " + std::to_string(have));
  const std::uint64_t need = src.header_bytes + img.voxels() * bytes;
  if (have > need)
    imageError(src, "size mismatch: the raw file has " + std::to_string(have) + " bytes but " +
                        what + " take " + std::to_string(need) +
                        " (check dimensions, type and header_bytes)");
  checkImageMemory(src, img.voxels(), bytes);
  std::vector<unsigned char> buf(img.voxels() * bytes);
  in.readAt(src.header_bytes, buf.data(), buf.size());
  std::vector<std::int32_t> file(img.voxels());
  decodeLabels(buf.data(), file.size(), src.type, src.big_endian, file.data(), src);
  img.value = toXSlowest(std::move(file), img.n, src.axes);
  return img;
}
void writeRawImage(const VoxelImage& image, const std::filesystem::path& path, ScalarType type) {
  const std::size_t b = static_cast<std::size_t>(bytesOf(type));
  std::string out(image.voxels() * b, '\0');
  std::size_t at = 0;
  for (std::size_t k = 0; k < static_cast<std::size_t>(image.n[2]); ++k)
    for (std::size_t j = 0; j < static_cast<std::size_t>(image.n[1]); ++j)
      for (std::size_t i = 0; i < static_cast<std::size_t>(image.n[0]); ++i, at += b) {
        // little endian, the low bytes of the label
        std::uint64_t v = static_cast<std::uint64_t>(
            static_cast<std::int64_t>(image.value[xSlowest(image.n, i, j, k)]));
        for (std::size_t c = 0; c < b; ++c, v >>= 8)
          out[at + c] = static_cast<char>(v & 0xff);
      }
  core::writeFileAtomically(path, out);
}

} // namespace lamina::micro::detail
