#pragma once
/// @file unit_cell.hpp
/// @brief A voxel unit cell: inclusions placed from a CellSpec and the phase
/// map sampled at voxel centres.
///
/// Contract: placement is done in continuous coordinates and does not depend
/// on the resolution, so refining the grid refines the same geometry. With a
/// target volume fraction the group's lengths are scaled uniformly so that
/// its copies reach the target exactly (analytic volumes); the voxel fraction
/// actually reached is reported in UnitCell::voxel_fraction.

#include "micro/cell.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace lamina::micro {

/// One voxel cut by an inclusion's interface (composite_voxel.hpp).
struct CompositeVoxel {
  std::size_t index = 0;  ///< voxel (C order, x slowest)
  int inside = 0;         ///< phase of the inclusion
  int outside = 0;        ///< phase around it (the matrix, phase 0)
  double fraction = 0;    ///< volume fraction of `inside` in the voxel, in (0, 1)
  Eigen::Vector3d normal; ///< unit interface normal (pointing out of the inclusion)
  int inclusion = -1;     ///< the inclusion whose interface gives the normal (UnitCell::inclusions)
};

/// One voxel whose yarn phase is rotated to the tangent of the yarn's
/// centre line (yarn_orientation.hpp): its stiffness is
/// C.rotated(materials::axisRotation(axis, angle)).
struct OrientedVoxel {
  std::size_t index = 0; ///< voxel (C order, x slowest)
  int phase = 0;         ///< the yarn's phase, whose stiffness is rotated
  int axis = 1;          ///< rotation axis: the yarn's width axis (0=x, 1=y, 2=z)
  double angle = 0;      ///< right-handed rotation about e_axis (radians)
};

/// @return the element of @p list (CompositeVoxel or OrientedVoxel, sorted
/// by voxel index) for voxel @p index, nullptr if it has none
template <class Voxel>
const Voxel* findVoxel(const std::vector<Voxel>& list, std::size_t index) {
  const auto it = std::lower_bound(list.begin(), list.end(), index,
                                   [](const Voxel& v, std::size_t i) { return v.index < i; });
  return it != list.end() && it->index == index ? &*it : nullptr;
}

/// A unit cell with its phase map.
struct UnitCell {
  std::array<int, 3> n{0, 0, 0};                  ///< voxels along x, y, z
  Eigen::Vector3d size = Eigen::Vector3d::Ones(); ///< edge lengths
  std::vector<std::int32_t> phase;     ///< phase index per voxel, C order, x slowest: (i*n1+j)*n2+k
  std::vector<Inclusion> inclusions;   ///< every placed inclusion
  std::vector<double> target_fraction; ///< per group: the requested fraction (NaN if none)
  std::vector<double> analytic_fraction;  ///< per group: analytic volume / cell volume
  std::vector<double> voxel_fraction;     ///< per phase: fraction of voxels
  int phase_count = 0;                    ///< number of phases
  std::vector<CompositeVoxel> composites; ///< cut voxels (empty without composite voxels)
  /// voxels whose yarn phase is rotated along the yarn's path, in voxel
  /// order (yarn_orientation.hpp; empty when no yarn follows its path)
  std::vector<OrientedVoxel> oriented;

  /// @return the number of voxels
  std::size_t voxels() const { return phase.size(); }
  /// @return the linear index of voxel (i, j, k)
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * static_cast<std::size_t>(n[1]) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(n[2]) +
           static_cast<std::size_t>(k);
  }
  /// Recomputes voxel_fraction from the phase map and the composite voxels
  /// (a cut voxel counts its fraction to each of its two phases).
  void countFractions();
};

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

/// The voxel index range (unwrapped, inclusive; may extend past the grid and
/// wraps periodically) that can hold part of @p inc, never longer than the grid.
void voxelRange(const Inclusion& inc, const std::array<int, 3>& n, const Eigen::Vector3d& size,
                std::array<int, 3>& lo, std::array<int, 3>& hi);

/// Flat index (x slowest, z fastest) of voxel (@p i, @p j, @p k) of a grid
/// of @p n voxels, each index wrapped periodically into [0, n): the unwrapped
/// indices voxelRange() gives land on their periodic copy.
inline std::size_t wrappedVoxelIndex(int i, int j, int k, const std::array<int, 3>& n) {
  auto wrap = [](int a, int m) { return static_cast<std::size_t>(((a % m) + m) % m); };
  return (wrap(i, n[0]) * static_cast<std::size_t>(n[1]) + wrap(j, n[1])) *
             static_cast<std::size_t>(n[2]) +
         wrap(k, n[2]);
}

/// Centre of the voxel of flat index @p index (wrappedVoxelIndex's order) in
/// a grid of @p n voxels of edges @p h.
inline Eigen::Vector3d voxelCentre(std::size_t index, const std::array<int, 3>& n,
                                   const Eigen::Vector3d& h) {
  const auto n1 = static_cast<std::size_t>(n[1]), n2 = static_cast<std::size_t>(n[2]);
  return {(static_cast<double>(index / (n1 * n2)) + 0.5) * h[0],
          (static_cast<double>((index / n2) % n1) + 0.5) * h[1],
          (static_cast<double>(index % n2) + 0.5) * h[2]};
}

/// Calls @p visit(index) for every voxel (index wrapped periodically, C
/// order) whose centre lies inside @p inc, each once, from several OpenMP
/// threads at once (visit must be safe for distinct voxels): whole runs of
/// voxels inside or outside are decided at once (InsideQuery::runSide).
void forEachVoxelInside(const Inclusion& inc, const std::array<int, 3>& n,
                        const Eigen::Vector3d& size, const std::function<void(std::size_t)>& visit);

/// Samples a phase map from placed inclusions: voxel centre inside an
/// inclusion -> its phase, else phase 0.
std::vector<std::int32_t> voxelize(const std::vector<Inclusion>& inclusions,
                                   const std::array<int, 3>& n, const Eigen::Vector3d& size);

} // namespace lamina::micro
