#pragma once
/// @file cell_operator.hpp
/// @brief The discrete periodic cell problem: the rotated staggered-grid
/// gradient and its transpose, and the stiffness operator A = D^T C D.
///
/// Discretization (why this one): Willot's rotated scheme (F. Willot, C. R.
/// Mecanique 343 (2015) 232-245). Displacements live at the voxel corners
/// (nodes); the strain of a voxel is the gradient at its centre, i.e. the
/// trilinear hexahedron evaluated at one point:
///   d u / d x (voxel) = 1/(4 h_x) * sum over the 4 x-edges of (u(x+h) - u(x)).
/// With one strain per voxel the element has a single volumetric constraint
/// against three nodal unknowns, so a nearly incompressible matrix (nu =
/// 0.494 here) does not lock, where fully integrated 8-point hexes overestimate
/// shear moduli by tens of per cent at 32^3. Its zero-energy (hourglass) modes
/// are exactly the Fourier modes where the discrete wave vector q vanishes;
/// they carry no strain for any phase stiffness, so excluding them in the
/// Green operator leaves effective moduli untouched. A = D^T C D is symmetric
/// positive semi-definite, so conjugate gradients apply, and for a
/// homogeneous reference medium it is diagonalised by the FFT with a real 3x3
/// symbol K0(q) = mu0 |q|^2 I + (lambda0 + mu0) q q^T that is inverted in
/// closed form (green_operator.hpp). Per voxel only the phase index is stored.
///
/// Units: strains and C in lamina order (engineering shear), the voxel
/// volume is left out of A (it cancels between A, the right-hand side and the
/// preconditioner).

#include "homogenize/distribution.hpp"
#include "homogenize/grid.hpp"
#include "materials/stiffness.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace lamina::homogenize {

/// Applies the cell's stiffness operator.
class CellOperator {
public:
  /// @param grid the voxel grid
  /// @param phase phase index per voxel of this process's slab
  ///   (dist.localSize() entries, each < C.size())
  /// @param C stiffness per phase, lamina order (Pa)
  /// @param dist the slab decomposition (must outlive this object)
  CellOperator(const Grid& grid, std::vector<std::int32_t> phase,
               const std::vector<materials::Stiffness>& C, const Distribution& dist);

  /// Computes f = D^T C (E + D u) and, if @p average is not null, the
  /// volume-averaged stress <C (E + D u)> (lamina order). Distributed: u and
  /// f are this rank's slab (3 x dist.localSize()), the halo planes of u are
  /// exchanged here, and average and energy are summed over all ranks.
  /// @param u nodal displacement (3 x N, component-major), or nullptr for u = 0
  /// @param E macroscopic strain (lamina order, engineering shear)
  /// @param f nodal forces (3 x N) on exit, or nullptr to skip the divergence
  /// @param average if not null: <sigma> on exit
  /// @param energy if not null: sum over voxels of eps : C : eps on exit,
  ///   which for E = 0 is u^T A u (CG needs it, and it costs no extra pass)
  void apply(const double* u, const std::array<double, 6>& E, double* f,
             std::array<double, 6>* average, double* energy = nullptr) const;
  /// The same in single precision, for conjugate gradients at loose
  /// tolerances: strains, stresses and forces in float (twice the SIMD lanes,
  /// half the memory traffic), the composite voxels' 6x6 products in double;
  /// <sigma> and the energy are summed in float along one voxel row (n2
  /// voxels) and in double across rows and ranks.
  void apply(const float* u, const std::array<double, 6>& E, float* f,
             std::array<double, 6>* average, double* energy = nullptr) const;

  /// @return the grid
  const Grid& grid() const { return grid_; }

private:
  // the scratch fields of one precision: halo node planes of u and per
  // thread two voxel planes of stress (6 per voxel)
  template <class T>
  struct Work {
    std::vector<T> halo_lo, halo_hi; // node planes x0 - 1, x0 + nx of u
    std::vector<T> planes;           // per thread: two voxel planes of stress
  };
  template <class T>
  Work<T>& work() const;
  template <class T>
  const T* lame() const;
  template <class T>
  void applyImpl(const T* u, const std::array<double, 6>& E, T* f, std::array<double, 6>* average,
                 double* energy) const;
  std::size_t componentStride() const;
  std::size_t planeStride() const;
  template <class T>
  const T* nodeRow(const T* u, int c, int p, int j) const;
  template <class T>
  void stressPlane(int i, const T* u, const std::array<T, 6>& E, T* S, double* acc, double* energy,
                   T* scratch) const;
  template <class T>
  void isotropicRow(const std::int32_t* phase, const std::array<T, 6>& E, T* S, double* acc,
                    double* energy, T* scratch) const;
  template <class T>
  void anisotropicVoxels(std::size_t row_index, const std::int32_t* phase,
                         const std::array<T, 6>& E, T* S, double* acc, double* energy,
                         const T* scratch) const;
  void stress6x6(std::size_t ph, const double e[6], double sv[6]) const;
  template <class T>
  void divergencePlane(int i, const T* prev, const T* cur, T* f, T* scratch) const;

  Grid grid_;
  const Distribution& dist_;
  std::vector<std::int32_t> phase_;    // this slab's voxels
  std::vector<std::int32_t> phase_lo_; // voxel plane x0 - 1 (halo)
  std::vector<double> C_;              // 36 per phase, row-major, lamina order
  std::vector<char> iso_;              // per phase: isotropic (use lame_)
  std::vector<double> lame_;           // per phase: lambda, mu (0, 0 for an anisotropic phase)
  std::vector<float> lame_f_;          // the same rounded to float
  // The voxels of anisotropic phases (composite voxels: a few per cent), per
  // voxel row r = (i + 1) n1 + j of planes i = -1 (halo) .. nx-1: their z
  // indices aniso_k_[aniso_start_[r] .. aniso_start_[r + 1]). isotropicRow
  // gives them zero stress; anisotropicVoxels then sets theirs.
  std::vector<std::size_t> aniso_start_;
  std::vector<std::int32_t> aniso_k_;
  mutable Work<double> work_d_;         // double-precision apply()
  mutable Work<float> work_f_;          // single-precision apply()
  mutable std::vector<double> uniform_; // apply() with u = 0: per phase C_p E and E : C_p : E
};

} // namespace lamina::homogenize
