#pragma once
/// @file stencil.hpp
/// @brief The rotated staggered-grid stencil (Willot 2015) on one row of
/// voxels along z: the gradient of the nodal displacement and its transpose,
/// shared by the linear cell operator (cell_operator.hpp) and the field
/// operator of the nonlinear solver (field_operator.hpp).
///
/// The strain of voxel (i, j, k) is the gradient of the trilinear
/// interpolant of its 8 corner nodes at its centre. It factorises into
/// differences (D) and averages (A) along each axis, d/dx = Dx Ay Az, d/dy =
/// Ax Dy Az, d/dz = Ax Ay Dz: per node column k the four node rows (i, j),
/// (i+1, j), (i, j+1), (i+1, j+1) give X = Dx Ay u, Y = Ax Dy u, Z = Ax Ay u,
/// finished along z per voxel (k, k+1). The nodal force f = D^T sigma of
/// node row (i, j) gathers the transposed weights from the voxel rows (i-1,
/// j-1), (i-1, j), (i, j-1), (i, j) the same way. Rows are periodic in z.
/// Strains in lamina order with engineering shear, stresses in lamina order.

#include "homogenize/grid.hpp"

#include <array>
#include <cstddef>

namespace lamina::homogenize::stencil {

/// Length of one scratch row: n2 + 1 (one wrapped entry).
inline std::size_t rowLength(const Grid& g) {
  return static_cast<std::size_t>(g.n[2]) + 1;
}

/// Column sums of one displacement component: X = (b - a) + (d - c),
/// Y = (c + d) - (a + b), Z = (a + b) + (c + d) for k < n2, and entry n2 a
/// copy of entry 0 (periodic in z). T: double, or float for the linear
/// solver's single-precision operator (cell_operator.hpp).
/// @param a, b, c, d node rows (i, j), (i+1, j), (i, j+1), (i+1, j+1)
template <class T>
void gradientSums(const T* a, const T* b, const T* c, const T* d, int n2, T* X, T* Y, T* Z);

/// The column sums of a voxel row (as gradientSums leaves them) and the
/// grid factors 1/(4 h): strainAt() finishes one voxel's strain from them.
template <class T>
struct RowSums {
  /// @param sums X, Y, Z of component c at sums + (3 c + s) * L (s = 0, 1, 2)
  RowSums(const T* sums, std::size_t L, const Grid& grid)
      : X0(sums), Y0(sums + L), Z0(sums + 2 * L), X1(sums + 3 * L), Y1(sums + 4 * L),
        Z1(sums + 5 * L), X2(sums + 6 * L), Y2(sums + 7 * L), Z2(sums + 8 * L),
        cx(static_cast<T>(0.25 / grid.h[0])), cy(static_cast<T>(0.25 / grid.h[1])),
        cz(static_cast<T>(0.25 / grid.h[2])) {}
  const T *X0, *Y0, *Z0, *X1, *Y1, *Z1, *X2, *Y2, *Z2; ///< column sums per component
  T cx, cy, cz;                                        ///< 1 / (4 h) per axis
};

/// eps = E + D u of voxel k of a row (lamina order, engineering shear):
/// d u_c / d x from X (averaged over k, k+1), d/dy from Y, d/dz from Z
/// (difference). Inline: the cell operator's SIMD row loop calls it.
template <class T>
inline void strainAt(const RowSums<T>& s, const std::array<T, 6>& E, int k, T& e0, T& e1, T& e2,
                     T& e3, T& e4, T& e5) {
  e0 = E[0] + s.cx * (s.X0[k] + s.X0[k + 1]);
  e1 = E[1] + s.cy * (s.Y1[k] + s.Y1[k + 1]);
  e2 = E[2] + s.cz * (s.Z2[k + 1] - s.Z2[k]);
  e3 = E[3] + s.cy * (s.Y0[k] + s.Y0[k + 1]) + s.cx * (s.X1[k] + s.X1[k + 1]);
  e4 = E[4] + s.cz * (s.Z1[k + 1] - s.Z1[k]) + s.cy * (s.Y2[k] + s.Y2[k + 1]);
  e5 = E[5] + s.cz * (s.Z0[k + 1] - s.Z0[k]) + s.cx * (s.X2[k] + s.X2[k + 1]);
}

/// Strain of a voxel row, eps = E + D u, from the column sums of the three
/// components (sums + (3 c + s) * L holds X, Y, Z of component c, s = 0, 1,
/// 2; L = rowLength).
/// @param eps the six strain rows (lamina order, engineering shear), n2 each
void strainRow(const double* sums, std::size_t L, const Grid& grid, const std::array<double, 6>& E,
               double* const eps[6]);

/// Nodal forces of a node row, f = D^T sigma, from the stresses of the four
/// voxel rows around it (lamina order, 6 rows each, n2 entries).
/// @param prev_j, prev_m voxel rows (i-1, j) and (i-1, j-1)
/// @param cur_j, cur_m voxel rows (i, j) and (i, j-1)
/// @param scratch 9 * rowLength doubles
/// @param f the three force rows (x, y, z components), n2 each
void divergenceRow(const double* const prev_j[6], const double* const prev_m[6],
                   const double* const cur_j[6], const double* const cur_m[6], const Grid& grid,
                   double* scratch, double* const f[3]);

/// Rows of x-combinations per voxel row (xCombinations).
inline constexpr int kXCombinations = 8;

/// The combinations across x of the stresses of one voxel row that the
/// divergence of the node rows next to it takes: prev - cur of sigma_xx,
/// xy, xz and prev + cur of sigma_xy, yy, yz, xz, zz, in rows of L =
/// rowLength entries where index k+1 holds voxel k and index 0 voxel n2-1
/// (periodic). Each voxel row serves two node rows (j and j+1), so forming
/// them once halves the reads of the stress planes.
/// @param prev, cur the voxel row (j) of the planes below and above the node plane
/// @param out kXCombinations rows of L entries
template <class T>
void xCombinations(const T* const prev[6], const T* const cur[6], int n2, T* out);

/// Nodal forces of a node row, f = D^T sigma, from the x-combinations of
/// voxel rows j (@p cj) and j-1 (@p cm): the same sums as divergenceRow.
/// @param f the three force rows (x, y, z components), n2 each
template <class T>
void divergenceFromCombinations(const T* cj, const T* cm, const Grid& grid, T* const f[3]);

} // namespace lamina::homogenize::stencil
