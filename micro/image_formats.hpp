#pragma once
/// @file image_formats.hpp
/// @brief The per-format readers and writers behind image_io.hpp (internal to
/// micro). Readers return the whole image in lamina's layout (x slowest);
/// probes read the dimensions only.

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "micro/voxel_image.hpp"

#include <string>

namespace lamina::micro::detail {

/// HDF5: integer dataset src.dataset (default /phases), rank 3, axes per src.axes.
VoxelImage readHdf5Image(const ImageSource& src);
/// @return the dimensions (x, y, z) of the HDF5 dataset
std::array<int, 3> probeHdf5Image(const ImageSource& src);
/// Writes /NAME (int32) with size_x/y/z attributes.
void writeHdf5Image(const VoxelImage& image, const std::filesystem::path& path,
                    const ImageWriteOptions& options);

/// VTK XML ImageData: CellData (or PointData) array, any encoding.
VoxelImage readVtiImage(const ImageSource& src);
/// @return the dimensions (x, y, z) of the VTI image
std::array<int, 3> probeVtiImage(const ImageSource& src);
/// Writes an ImageData file with the labels as Int32 CellData.
void writeVtiImage(const VoxelImage& image, const std::filesystem::path& path,
                   const ImageWriteOptions& options);

/// Raw: src.dimensions of src.type in src byte order after src.header_bytes.
VoxelImage readRawImage(const ImageSource& src);
/// Writes x fastest, little endian, in @p type.
void writeRawImage(const VoxelImage& image, const std::filesystem::path& path, ScalarType type);

/// TIFF stack: one page per z slice (width x, height y), 8/16/32-bit integers.
VoxelImage readTiffImage(const ImageSource& src);
/// @return the dimensions (x, y, z) of the TIFF stack
std::array<int, 3> probeTiffImage(const ImageSource& src);
/// Writes one page per z slice in the smallest unsigned type holding the labels.
void writeTiffImage(const VoxelImage& image, const std::filesystem::path& path);

/// Opens the image file of @p src after the checks of core::InputFile (a
/// regular file of at most core::kMaxImageBytes); errors name the image, the
/// cell file and its key.
core::InputFile openImage(const ImageSource& src);

/// Throws lamina::Error "MESSAGE" with the file and key of @p src.
[[noreturn]] void imageError(const ImageSource& src, const std::string& message);

/// Checks that an image of @p voxels labels, read through a buffer of
/// @p bytes_per_voxel file bytes, fits in memory (lamina::Error otherwise).
void checkImageMemory(const ImageSource& src, std::size_t voxels, std::size_t bytes_per_voxel);

/// Decodes @p count elements of @p type at @p data (byte order @p big_endian)
/// into labels; an element outside the int32 range is an error.
void decodeLabels(const unsigned char* data, std::size_t count, ScalarType type, bool big_endian,
                  std::int32_t* out, const ImageSource& src);

/// @return the smallest unsigned type that holds every label of @p image
/// (labels must be non-negative; negative labels give Int32)
ScalarType smallestType(const VoxelImage& image);

/// @return @p file (labels listed in @p order, dimensions @p n = x, y, z) in
/// lamina's layout (x slowest); Zyx input (x fastest) is transposed
std::vector<std::int32_t> toXSlowest(std::vector<std::int32_t> file, const std::array<int, 3>& n,
                                     AxisOrder order);

/// @return the voxel index of lamina's layout (x slowest) for (i, j, k)
inline std::size_t xSlowest(const std::array<int, 3>& n, std::size_t i, std::size_t j,
                            std::size_t k) {
  return (i * static_cast<std::size_t>(n[1]) + j) * static_cast<std::size_t>(n[2]) + k;
}

} // namespace lamina::micro::detail
