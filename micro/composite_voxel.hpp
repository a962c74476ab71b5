#pragma once
/// @file composite_voxel.hpp
/// @brief Composite voxels (Kabel, Merkert and Schneider, "Use of composite
/// voxels in FFT-based homogenization", CMAME 2015): a voxel cut by the
/// interface of a generated inclusion gets the stiffness of a laminate of its
/// two phases, with the sub-voxel volume fraction and the interface normal.
///
/// Laminate formula (exact for a flat interface; strain jumps only across the
/// normal n, tractions continue): with B(n) the 6x3 map a -> sym(a (x) n) in
/// lamina order (engineering shear; B^T maps a stress to its traction),
/// K_i = B^T C_i B, dC = C_1 - C_2, and fractions c_1 + c_2 = 1,
///   C = c_1 C_1 + c_2 C_2 - c_1 c_2 dC B (c_2 K_1 + c_1 K_2)^-1 B^T dC.
///
/// Detection and fraction: a voxel is cut by a curved inclusion (sphere,
/// ellipsoid, fibre) when its 8 corners are not all inside or all outside
/// it; its fraction is then counted on s^3 sub-voxel points (s =
/// kSubSamples). A layer's interfaces are planes: its fraction in every
/// voxel is exact (boxFractionBelowPlane over its nearby slabs), so thin
/// layers and planes along sub-sample rows are counted right. The normal is
/// the gradient direction of the inclusion's surface at the voxel centre. A
/// voxel cut by two inclusions keeps the phase of its centre (as without
/// composite voxels).

#include "materials/stiffness.hpp"
#include "micro/voxel_cell.hpp"

#include <Eigen/Dense>

#include <cstdint>
#include <vector>

namespace lamina::micro {

/// Sub-samples per voxel edge used to measure a cut voxel's fraction.
inline constexpr int kSubSamples = 10;

/// @return the laminate stiffness of @p C1 (fraction @p c1) and @p C2 with
/// interface normal @p n (formula above; lamina order, Pa)
materials::Stiffness laminateStiffness(const materials::Stiffness& C1,
                                       const materials::Stiffness& C2, double c1,
                                       const Eigen::Vector3d& n);

/// @return the fraction of the box of edges @p h centred at the origin that
/// lies on the side nu . x <= @p a of the plane with unit normal @p nu (exact:
/// inclusion-exclusion over the box corners; components of nu below 1e-9 of
/// the box's extent along nu are taken as zero)
double boxFractionBelowPlane(const Eigen::Vector3d& h, const Eigen::Vector3d& nu, double a);

/// @return the voxels of the grid (@p n voxels, cell @p size) cut by the
/// interfaces of @p inclusions, with fraction and normal; @p phase is the
/// centre-sampled phase map (voxelize()) and is updated for cut voxels whose
/// sub-samples all fall on one side
std::vector<CompositeVoxel> findCompositeVoxels(const std::vector<Inclusion>& inclusions,
                                                const std::array<int, 3>& n,
                                                const Eigen::Vector3d& size,
                                                std::vector<std::int32_t>& phase);

/// The per-voxel materials the homogenizer takes: a phase map and one
/// stiffness and density per entry. Without composite voxels they are the
/// cell's; with them each cut voxel gets its own entry (appended after the
/// cell's phases) holding its laminate stiffness and mixed density. A voxel
/// of a yarn that follows its path (UnitCell::oriented) takes the yarn
/// phase's stiffness rotated to the path's tangent: the yarn side of a cut
/// voxel's laminate, or, for a whole voxel, an entry shared by the voxels of
/// equal rotation (bit for bit: a row across the yarn's width).
struct VoxelMaterials {
  std::vector<std::int32_t> phase;     ///< entry per voxel
  std::vector<materials::Stiffness> C; ///< per entry (lamina order, Pa)
  std::vector<double> density;         ///< per entry (kg/m^3)
};

/// Builds the VoxelMaterials of @p cell from the phase stiffnesses @p C and
/// densities @p density (laminate stiffness per composite voxel, rotated
/// stiffness per rotation of whole oriented voxels; entries: the phases,
/// then the composite voxels in voxel order, then the distinct rotations
/// (phase, axis, angle) in ascending order).
VoxelMaterials voxelMaterials(const UnitCell& cell, const std::vector<materials::Stiffness>& C,
                              const std::vector<double>& density);

} // namespace lamina::micro
