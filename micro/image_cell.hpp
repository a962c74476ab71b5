#pragma once
/// @file image_cell.hpp
/// @brief Unit cells whose voxels come from an image file (`[cell] image =
/// "PATH"`): the cell-file keys, label-to-phase mapping, and the labelled
/// image of any cell (what `micro --out` writes).
///
/// A phase owns the image value given by its `id = K`. Keys (docs/homogenize.md):
/// image, format, dataset, axes, dimensions, type, byte_order, header_bytes,
/// crop = { start, count }, downsample, voxel_size.

#include "micro/image_io.hpp"
#include "micro/unit_cell.hpp"

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

/// Builds the unit cell of an image cell: reads the image (crop,
/// down-sampling), maps each label to the phase with that id, sets the size
/// (voxel_size key, else the file's spacing, else unit cubic voxels, unless
/// the cell gives `size`). Throws lamina::Error naming the file and
/// `phases` for a label no phase owns.
UnitCell buildImageCell(const CellSpec& spec);

/// @return the image value of each phase: its `id`, else its index
std::vector<std::int32_t> phaseLabels(const CellSpec& spec);

/// @return @p cell's phase map as an image of labels (phaseLabels) with its
/// voxel spacing (what `micro --out` writes, so that the file reads back
/// through an image cell with the same phases)
VoxelImage labelImage(const CellSpec& spec, const UnitCell& cell);

} // namespace lamina::micro
