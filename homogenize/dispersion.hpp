#pragma once
/// @file dispersion.hpp
/// @brief Micro-inertia of a unit cell: the linear dispersion tensor D_lin
/// of the GVBO chapter, section 4.3 (eqs. 35, 38, 39), from the displacement
/// fluctuations of the six load cases of the cell problem.
///
/// Method (docs/homogenize-solver.md, "Micro-inertia"):
/// - H_k, the periodic displacement fluctuation of unit load case k (lamina
///   order, engineering shear), is the nodal solution u of the cell problem
///   (cell_operator.hpp), handed over by Homogenizer::setDisplacementSink.
/// - h_k solves eq. 39, sym grad h_k = sym grad H_k + (Delta rho / rho) T_k
///   with Delta rho(y) = rho_bar - rho(y) and T_k the strain tensor of unit
///   load k. The density term is in general not a compatible strain, so h_k
///   is the least-squares solution on the periodic grid: with the rotated
///   gradient of the cell problem (symbol i e^{i sum xi/2} q, q real) and
///   g = i e^{i sum xi/2} h_hat, each Fourier mode minimizes
///   |sym(q (x) g) - e_hat|^2, i.e. g = A(q)^-1 e_hat q with
///   A(q) = (|q|^2 I + q q^T)/2 and A^-1 = 2/|q|^2 (I - q q^T/(2|q|^2)).
///   Modes with q = 0 (mean, hourglass) get h = 0 (the minimum-norm
///   solution; <h> = 0 as eq. 39 asks). The part of e that no periodic h
///   reaches is the residual, reported per load case relative to |e|.
/// - zeta^2 D_lin_IJ = rho_bar <h_I . h_J> (eq. 38) with h in metres when the
///   grid spacing is in metres: a symmetric positive semi-definite 6x6 in
///   lamina order, the coefficient of the engineering strain acceleration in
///   eq. 35 (same convention as C), in kg/m. The cell average is the exact
///   integral of the trilinear interpolant of the nodal h (the consistent
///   mass symbol prod_d (2 + cos xi_d)/3 in Fourier space), so voxel-aligned
///   laminates come out exact.
///
/// - Reduced-order cells (reduced_order_builder.hpp): the matrices R and Q
///   of eq. 40, R^(alpha beta)_IJ = rho_bar <S^(alpha)_I . S^(beta)_J> and
///   Q^(alpha)_IJ = rho_bar <h_I . S^(alpha)_J>, with the eigenstrain
///   influence functions S (addInfluence), the same cell average and the
///   same convention (the modes with q = 0 dropped, so every field has zero
///   mean and no hourglass part). The spectra of all influence functions
///   are kept: 3 x complexSize() complex doubles each (about 3 N doubles).
///   D_nonlin itself (eq. 40) needs the eigenstrain rates of the inelastic
///   phases: it belongs to the reduced-order law, not to the cell.

#include "homogenize/grid.hpp"
#include "materials/stiffness.hpp"

#include <array>
#include <complex>
#include <cstdint>
#include <vector>

namespace lamina::homogenize {

/// The micro-inertia of a cell.
struct Dispersion {
  materials::Matrix6 D = materials::Matrix6::Zero(); ///< zeta^2 D_lin (kg/m), lamina order
  std::array<double, 6> residual{};                  ///< least-squares residual of eq. 39 per case
  std::array<double, 6> H_rms{}; ///< rms displacement fluctuation per unit strain (m)
  std::array<double, 6> h_rms{}; ///< rms of h (m)
};

/// The eq. 40 averages of one eigenstrain influence function S (kg/m).
struct InfluenceAverages {
  std::array<double, 6> with_h{}; ///< rho_bar <h_I . S>, I = 0..5 (a column of Q)
  /// rho_bar <S_m . S> for every influence function m added before S, in
  /// the order added, then rho_bar <S . S> (a row of R up to its diagonal)
  std::vector<double> with_s;
};

/// Collects the six load cases and forms zeta^2 D_lin (and, for
/// reduced-order cells, the averages of eq. 40).
class DispersionAccumulator {
public:
  /// @param grid the cell grid (voxel lengths in metres for an SI result)
  /// @param phase phase index per voxel
  /// @param density density per phase (kg/m^3)
  DispersionAccumulator(const Grid& grid, const std::vector<std::int32_t>& phase,
                        const std::vector<double>& density);

  /// Takes load case @p k (0-5, lamina order): @p u is its nodal displacement
  /// fluctuation H_k (3 x N, component-major, as the cell problem's).
  void addLoadCase(int k, const double* u);

  /// @return D and diagnostics; throws lamina::Error unless all six cases
  /// were added
  Dispersion result() const;

  /// @return the mean density rho_bar (kg/m^3)
  double meanDensity() const { return rho_bar_; }

  /// Takes an eigenstrain influence function @p S (3 x N, component-major,
  /// nodal as H; metres per unit eigenstrain) once the six load cases are
  /// in: keeps its spectrum (the modes with q = 0 set to zero, as h's) and
  /// returns its averages with the six h and with every influence function
  /// taken so far (itself last), in one pass over the modes. Throws
  /// lamina::Error unless all six load cases were added.
  InfluenceAverages addInfluence(const double* S);

  /// @return the number of influence functions taken
  std::size_t influences() const { return s_hat_of_.size(); }

  /// @return the doubles kept per influence function (2 x 3 x complexSize)
  std::size_t doublesPerInfluence() const { return 6 * grid_.complexSize(); }

private:
  using Complex = std::complex<double>;
  /// the r2c spectrum of a nodal field (3 x N) as 3 x complexSize complex values
  std::vector<Complex> spectrum(const double* u) const;
  Grid grid_;
  double rho_bar_ = 0;
  std::vector<Complex> s_hat_;                // FFT of Delta rho / rho_bar
  std::array<std::vector<Complex>, 6> h_hat_; // FFT of h_k, 3 x complexSize each
  std::array<bool, 6> have_{};                // which cases were added
  std::vector<std::vector<Complex>> s_hat_of_; // influence functions, 3 x complexSize each
  Dispersion out_;
};

} // namespace lamina::homogenize
