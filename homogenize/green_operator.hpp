#pragma once
/// @file green_operator.hpp
/// @brief Preconditioner of the cell problem: the exact inverse of the
/// stiffness operator of a homogeneous isotropic reference medium, applied
/// through the FFT (the discrete Green operator of the rotated scheme).
///
/// In Fourier space the rotated gradient of a mode exp(i xi . x) is
/// i e^{i (xi_1 + xi_2 + xi_3)/2} q with the real vector
///   q_1 = 2 sin(xi_1/2) cos(xi_2/2) cos(xi_3/2) / h_1   (and cyclically),
/// so the reference operator D^T C0 D has the real symbol
///   K0 = mu0 |q|^2 I + (lambda0 + mu0) q q^T,
/// inverted in closed form:
///   K0^-1 = (I - (lambda0 + mu0)/(lambda0 + 2 mu0) q q^T/|q|^2) / (mu0 |q|^2).
/// Modes with q = 0 (the mean and the hourglass modes) are mapped to zero.

#include "homogenize/fft.hpp"

#include <vector>

namespace lamina::homogenize {

/// z = K0^+ r for nodal force fields.
class GreenOperator {
public:
  /// @param grid the grid; @param lambda0, mu0 reference Lame constants (Pa);
  /// @param fft plans for @p grid (must outlive this object)
  GreenOperator(const Grid& grid, double lambda0, double mu0, const VectorFft& fft);
  /// z = K0^+ r (3 x N each; r is kept, z may not alias r).
  /// @return r^T z, summed in Fourier space (Parseval) during the solve
  double apply(const double* r, double* z) const;

private:
  Grid grid_;
  double lambda0_, mu0_;
  const VectorFft& fft_;
  std::vector<double> sin_[3], cos_[3]; // sin(xi/2), cos(xi/2) per axis
};

} // namespace lamina::homogenize
