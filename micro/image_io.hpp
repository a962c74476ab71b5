#pragma once
/// @file image_io.hpp
/// @brief Reading and writing voxel images in the formats image cells name:
/// HDF5, VTK ImageData (.vti), raw binary and multi-page TIFF.
///
/// Reading: the whole file is read (memory checked first), then the crop
/// window is cut out, then blocks of f x f x f voxels are reduced to one
/// (`downsample = f`): a block takes the label held by most of its voxels,
/// ties going to the smallest label. Every failure is a lamina::Error naming
/// the file and the key or dataset: a missing dataset, a wrong rank or type,
/// a truncated file, a size that does not match the cell.

#include "core/enum_names.hpp"
#include "micro/voxel_image.hpp"

namespace lamina::micro {

/// Reads the image @p src names and applies its crop and down-sampling.
VoxelImage readImage(const ImageSource& src);

/// @return the voxels along x, y, z that readImage(@p src) will return, from
/// the file's header only (no voxel data is read)
std::array<int, 3> imageShape(const ImageSource& src);

/// Writes @p image to @p path in @p format (labels as stored), atomically
/// (written aside, renamed into place). Raw files are written x fastest
/// (axes "zyx") in the smallest unsigned type that holds the labels, little
/// endian; @return the `[cell]` keys that read the file back (raw: dimensions,
/// type, byte order, axes), one `key = value` per line.
std::string writeImage(const VoxelImage& image, const std::filesystem::path& path,
                       ImageFormat format, const ImageWriteOptions& options = {});

/// Crops @p image to the window @p start, @p count (count 0: to the end);
/// throws lamina::Error naming @p src's file and `crop` if it leaves the image.
VoxelImage cropImage(const VoxelImage& image, const std::array<int, 3>& start,
                     const std::array<int, 3>& count, const ImageSource& src);

/// Down-samples @p image by the integer factor @p f (each dimension must be
/// divisible by f): every f^3 block becomes one voxel with the label most of
/// its voxels hold (ties: the smallest label).
VoxelImage downsampleImage(const VoxelImage& image, int f, const ImageSource& src);

} // namespace lamina::micro
