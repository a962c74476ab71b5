#pragma once
/// @file start_residual.hpp
/// @brief The right-hand side of a load case, b = -D^T C E (the residual of
/// conjugate gradients at x = 0), and the average stress <C E>, from the
/// phase map alone.
///
/// With u = 0 every voxel's stress is its phase's C_p E, so the nodal force
/// f = D^T sigma of a node whose 8 surrounding voxels share one phase is the
/// divergence of a uniform stress: exactly zero (each x-, y- and
/// z-difference of the stencil subtracts equal numbers). Only the runs of
/// nodes along z next to an interface are formed, with the stencil
/// functions the cell operator uses (stencil.hpp) on those runs, so b
/// equals CellOperator::apply with u = 0 bit for bit; the rest is
/// zero-filled. On the 128^3 sphere cell 1.9 % of the nodes (in 42 % of
/// the node rows) are next to an interface. The average sums the voxels'
/// stresses in the order the cell operator does with one thread (per
/// thread: its planes in order).

#include "homogenize/distribution.hpp"
#include "homogenize/grid.hpp"
#include "materials/stiffness.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace lamina::homogenize {

/// Forms b = -D^T C E and <C E> for a macroscopic strain E.
class StartResidual {
public:
  /// @param grid the voxel grid
  /// @param phase phase index per voxel of this process's slab
  ///   (dist.localSize() entries, each < C.size()); must outlive this object
  /// @param C stiffness per phase, lamina order (Pa); must outlive this object
  /// @param dist the slab decomposition (must outlive this object)
  StartResidual(const Grid& grid, const std::vector<std::int32_t>& phase,
                const std::vector<materials::Stiffness>& C, const Distribution& dist);

  /// Computes b = -D^T C E into @p b (3 x dist.localSize(), component-major,
  /// this rank's slab) and the volume average <C E> over all ranks.
  /// @tparam V double, or float (formed in double, rounded on the store)
  /// @param E macroscopic strain (lamina order, engineering shear)
  template <class V>
  void apply(const std::array<double, 6>& E, V* b, std::array<double, 6>& average) const;

  /// @return the fraction of this slab's node rows that are next to an interface
  double activeRowFraction() const;

private:
  Grid grid_;
  const Distribution& dist_;
  const std::vector<std::int32_t>& phase_;     // this slab's voxels
  const std::vector<materials::Stiffness>& C_; // per phase, lamina order
  // per voxel row r = (i + 1) n1 + j of planes i = -1 (halo) .. nx-1: its
  // phase if all its voxels share it, else -1
  std::vector<std::int32_t> row_phase_;
  // per voxel of the halo plane x0 - 1
  std::vector<std::int32_t> phase_lo_;
};

} // namespace lamina::homogenize
