#pragma once
/// @file field_operator.hpp
/// @brief The rotated staggered-grid gradient and its transpose on whole
/// fields, for solvers whose stress is not a per-phase C times the strain
/// (nonlinear laws, per-voxel tangents).
///
/// Same discretization as cell_operator.hpp (Willot's rotated scheme: nodal
/// displacements, one strain per voxel at its centre): the strain of voxel
/// (i, j, k) is
///     d u_c / d x_d = sum over its 8 corners (a, b, c in {0, 1}) of
///                     w_d(a, b, c) u_c(i + a, j + b, k + c),
///     w = ((2a - 1) / (4 h_x), (2b - 1) / (4 h_y), (2c - 1) / (4 h_z)),
/// and the nodal force f = D^T sigma gathers the transposed weights from the
/// 8 voxels around a node. Fields are component-major (component a of voxel v
/// at a * N + v), strains in lamina order with engineering shear, stresses in
/// lamina order.

#include "homogenize/grid.hpp"

#include <array>

namespace lamina::homogenize {

/// Gradient and divergence of fields on one periodic grid.
class FieldOperator {
public:
  /// @param grid the voxel grid
  explicit FieldOperator(const Grid& grid);

  /// eps = E + D u for every voxel (6 x N). @p u is 3 x N or nullptr (u = 0).
  void strain(const double* u, const std::array<double, 6>& E, double* eps) const;
  /// f = D^T sigma at every node (3 x N) from the voxel stresses (6 x N).
  void divergence(const double* sigma, double* f) const;
  /// @return the grid
  const Grid& grid() const { return grid_; }

private:
  Grid grid_;
};

} // namespace lamina::homogenize
