#pragma once
/// @file voxel_cell.hpp
/// @brief The data of a voxel unit cell: its phase map, its placed
/// inclusions and the voxels that carry more than a phase (composite voxels
/// cut by an interface, yarn voxels whose stiffness is rotated). The cell's
/// builders fill it (unit_cell.hpp for generated cells, image_cell.hpp for
/// image cells; composite_voxel.hpp and yarn_orientation.hpp for the special
/// voxels) and the homogenizer reads it.

#include "micro/inclusion.hpp"
#include "micro/phase_map.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
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
  /// phase index per voxel, C order, x slowest: (i*n1+j)*n2+k; owned, or
  /// borrowed from memory kept alive elsewhere (phase_map.hpp)
  PhaseMap phase;
  std::vector<Inclusion> inclusions;      ///< every placed inclusion
  std::vector<double> target_fraction;    ///< per group: the requested fraction (NaN if none)
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

} // namespace lamina::micro
