#pragma once
/// @file voxel_grid.hpp
/// @brief Inclusions on a periodic voxel grid: the voxel range an inclusion
/// can touch, flat indices wrapped periodically, voxel centres, and the
/// voxels whose centre lies inside an inclusion (the phase map of placed
/// inclusions). Grids are C order, x slowest: index (i n1 + j) n2 + k.

#include "micro/inclusion.hpp"

#include <Eigen/Dense>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace lamina::micro {

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
