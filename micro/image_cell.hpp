#pragma once
/// @file image_cell.hpp
/// @brief Unit cells whose voxels come from an image file (`[cell] image =
/// "PATH"`): label-to-phase mapping, and the labelled image of any cell
/// (what `micro --out` writes). The cell-file keys that say where the image
/// is and how to read it are read by image_source.hpp.
///
/// A phase owns the image value given by its `id = K`.

#include "micro/cell.hpp"
#include "micro/image_io.hpp"
#include "micro/voxel_cell.hpp"

namespace lamina::micro {

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
