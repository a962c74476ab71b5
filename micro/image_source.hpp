#pragma once
/// @file image_source.hpp
/// @brief The `[cell]` keys of an image cell read into an ImageSource (where
/// the voxels come from and how to read them). Keys (docs/homogenize.md):
/// image, format, dataset, axes, dimensions, type, byte_order, header_bytes,
/// crop = { start, count }, downsample, voxel_size.

#include "micro/voxel_image.hpp"

#include <string>

namespace lamina::core {
class TableReader;
}

namespace lamina::micro {

/// Reads the image keys of the `[cell]` table @p c (which has `image`) of the
/// cell file @p cell_file; the image path is resolved against its folder.
/// Throws lamina::Error naming the file and key on a bad value.
ImageSource readImageSource(const core::TableReader& c, const std::string& cell_file);

/// @return whether @p c holds a key that only image cells take (to reject
/// it, naming the key, in a generated cell); the key found goes to @p key
bool hasImageKey(const core::TableReader& c, std::string& key);

} // namespace lamina::micro
