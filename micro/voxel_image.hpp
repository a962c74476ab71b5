#pragma once
/// @file voxel_image.hpp
/// @brief A voxel image of integer labels (a segmented scan or a written
/// phase map), where a cell file says to find one and how one is written.
///
/// Layout in memory is lamina's everywhere: C order, x slowest, index
/// (i n1 + j) n2 + k. Each file format states its own order and the readers
/// convert (VTK ImageData and TIFF stacks store x fastest).

#include "core/enum_names.hpp"

#include <Eigen/Dense>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lamina::micro {

/// File formats an image cell can name and `micro --out` can write.
enum class ImageFormat {
  Hdf5, ///< .h5 / .hdf5: an integer dataset (`dataset`, default /phases)
  Vti,  ///< .vti: VTK XML ImageData (ascii, base64 binary, appended raw/base64, zlib)
  Raw,  ///< .raw / .bin: headerless array, dimensions/type/byte order from the cell
  Tiff, ///< .tif / .tiff: multi-page stack, one page per z slice
};

/// The cell-file names of ImageFormat (`format`).
inline constexpr auto kImageFormatNames =
    core::enumNames<ImageFormat>({{"hdf5", ImageFormat::Hdf5},
                                  {"vti", ImageFormat::Vti},
                                  {"raw", ImageFormat::Raw},
                                  {"tiff", ImageFormat::Tiff}});
/// The file extensions (lower case) of each ImageFormat, the usual one first.
inline constexpr auto kImageExtensions =
    core::enumNames<ImageFormat>({{".h5", ImageFormat::Hdf5},
                                  {".hdf5", ImageFormat::Hdf5},
                                  {".he5", ImageFormat::Hdf5},
                                  {".dream3d", ImageFormat::Hdf5},
                                  {".vti", ImageFormat::Vti},
                                  {".raw", ImageFormat::Raw},
                                  {".bin", ImageFormat::Raw},
                                  {".tif", ImageFormat::Tiff},
                                  {".tiff", ImageFormat::Tiff}});
/// @return the format named by @p path's extension (any case); false if none matches
bool formatFromExtension(const std::filesystem::path& path, ImageFormat& out);
/// @return the name of @p f ("hdf5", "vti", "raw", "tiff")
std::string toString(ImageFormat f);

/// Element types of raw files (and the integer types the readers accept).
enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64 };
/// The cell-file names of ScalarType (`type` of a raw image).
inline constexpr auto kScalarTypeNames =
    core::enumNames<ScalarType>({{"int8", ScalarType::Int8},
                                 {"uint8", ScalarType::UInt8},
                                 {"int16", ScalarType::Int16},
                                 {"uint16", ScalarType::UInt16},
                                 {"int32", ScalarType::Int32},
                                 {"uint32", ScalarType::UInt32},
                                 {"int64", ScalarType::Int64},
                                 {"uint64", ScalarType::UInt64}});
/// @return the name of @p t ("uint8", ...)
std::string toString(ScalarType t);
/// @return the size of one element of @p t in bytes
int bytesOf(ScalarType t);

/// How the dimensions of an HDF5 dataset or a raw file are listed, slowest
/// first: Xyz (lamina's own files, an h5py array indexed a[x, y, z]) or Zyx
/// (ImageJ, scanners, numpy arrays indexed a[z, y, x]: x fastest).
enum class AxisOrder { Xyz, Zyx };
/// The cell-file names of AxisOrder (`axes`): "xyz" x slowest, "zyx" x fastest.
inline constexpr auto kAxisOrderNames =
    core::enumNames<AxisOrder>({{"xyz", AxisOrder::Xyz}, {"zyx", AxisOrder::Zyx}});

/// Where an image cell's voxels come from (the `[cell]` keys of an image cell).
struct ImageSource {
  std::filesystem::path path;             ///< image file, resolved against the cell file's folder
  std::string key = "cell.image";         ///< key named in errors
  std::string cell_file;                  ///< the cell file (errors)
  ImageFormat format = ImageFormat::Hdf5; ///< from `format` or the extension
  std::string dataset;                    ///< HDF5 dataset / VTI array name ("" = default)
  AxisOrder axes = AxisOrder::Xyz;        ///< HDF5 and raw only
  std::array<int, 3> dimensions{0, 0, 0}; ///< raw only: voxels along x, y, z
  ScalarType type = ScalarType::UInt8;    ///< raw only
  bool big_endian = false;                ///< raw only
  std::uint64_t header_bytes = 0;         ///< raw only: bytes to skip
  std::array<int, 3> crop_start{0, 0, 0}; ///< first voxel kept (0-based)
  std::array<int, 3> crop_count{0, 0, 0}; ///< voxels kept (0 = up to the end)
  int downsample = 1;                     ///< integer factor: blocks of f^3 voxels -> one
};

/// An image of integer labels.
struct VoxelImage {
  std::array<int, 3> n{0, 0, 0};          ///< voxels along x, y, z
  std::vector<std::int32_t> value;        ///< label per voxel, x slowest
  std::optional<Eigen::Vector3d> spacing; ///< voxel edge lengths if the file gives them
  /// @return the number of voxels
  std::size_t voxels() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
           static_cast<std::size_t>(n[2]);
  }
};

/// How a .vti file stores its array.
enum class VtiEncoding {
  Ascii,    ///< numbers in the XML text
  Binary,   ///< base64 inside the DataArray element (format="binary")
  Appended, ///< raw bytes in the AppendedData section (format="appended", encoding="raw")
};
/// The names of VtiEncoding (`micro --vti-encoding`).
inline constexpr auto kVtiEncodingNames =
    core::enumNames<VtiEncoding>({{"ascii", VtiEncoding::Ascii},
                                  {"binary", VtiEncoding::Binary},
                                  {"appended", VtiEncoding::Appended}});

/// Options of writeImage.
struct ImageWriteOptions {
  VtiEncoding vti = VtiEncoding::Appended; ///< .vti only
  bool zlib = false;                       ///< .vti binary/appended: zlib-compressed blocks
  std::string name = "phases";             ///< HDF5 dataset (/NAME) or VTI array name
};

} // namespace lamina::micro
