#pragma once
/// @file unit_cell.hpp
/// @brief Building a voxel unit cell from a CellSpec: inclusions placed, the
/// phase map sampled at voxel centres (voxel_grid.hpp), composite voxels at
/// the interfaces (composite_voxel.hpp), yarn voxels oriented along their path
/// (yarn_orientation.hpp); an image cell is read instead (image_cell.hpp).
/// The cell's data is in voxel_cell.hpp.
///
/// Contract: placement is done in continuous coordinates and does not depend
/// on the resolution, so refining the grid refines the same geometry. With a
/// target volume fraction the group's lengths are scaled uniformly so that
/// its copies reach the target exactly (analytic volumes); the voxel fraction
/// actually reached is reported in UnitCell::voxel_fraction.

#include "micro/cell.hpp"
#include "micro/voxel_cell.hpp"
#include "micro/voxel_grid.hpp"

#include <array>
#include <vector>

namespace lamina::micro {

/// Whether generated cells use composite voxels when the cell file does not
/// say (`composite_voxels`): yes, they won the sphere benchmark (C at 32^3 20
/// to 30 times closer to the converged value than staircase voxels; the
/// measurement is in docs/homogenize.md, the test in
/// tests/homogenize/sphere_composite_convergence_test.cpp).
inline constexpr bool kCompositeVoxelsByDefault = true;

/// Places the inclusions of @p spec and samples the phase map at resolution
/// @p n (the spec's resolution if all zero), with composite voxels at the
/// interfaces if the spec asks (or by default, kCompositeVoxelsByDefault). Throws lamina::Error
/// naming the file and group when an inclusion does not fit in the cell or random placement fails
/// to reach the target.
UnitCell buildCell(const CellSpec& spec, std::array<int, 3> n = {0, 0, 0});

/// Places the inclusions only (continuous geometry); used by buildCell.
std::vector<Inclusion> placeInclusions(const CellSpec& spec, std::vector<double>& target,
                                       std::vector<double>& analytic);

} // namespace lamina::micro
