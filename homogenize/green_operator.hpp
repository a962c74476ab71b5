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
///
/// In single precision the transforms and the mode solve run in float: a
/// preconditioner perturbed by ~1e-7 relative, which conjugate gradients
/// tolerate down to residuals far below the tolerances it is used for. The
/// linear solver then hands it float fields too (r^T z is summed in double).

#include "homogenize/fft.hpp"

#include <vector>

namespace lamina::homogenize {

/// z = K0^+ r for nodal force fields.
class GreenOperator {
public:
  /// @param grid the grid; @param lambda0, mu0 reference Lame constants (Pa);
  /// @param fft plans for @p grid (must outlive this object; its
  /// distribution is the one of r and z)
  /// @param dist the distribution of the fields (sums of r^T z over ranks)
  GreenOperator(const Grid& grid, double lambda0, double mu0, VectorFft& fft,
                const Distribution& dist);
  /// z = K0^+ r (3 local slabs each; r is kept, z may not alias r). V:
  /// double, or float (the single-precision CG vectors of the linear solver).
  /// @return r^T z over all ranks, summed in Fourier space (Parseval)
  template <class V>
  double apply(const V* r, V* z) const;
  /// One fused conjugate-gradient step around the preconditioner:
  /// r -= alpha w (x += alpha p if @p x is not null), z = K0^+ r, and
  /// p = z + (r^T z / rz) p, in two passes over the fields besides the FFTs.
  /// When the new r^T z is at most @p rz_stop, CG has converged and will not
  /// use z or p again: the inverse transforms are skipped, only x += alpha p
  /// is done (p is left as it was).
  /// @return the new r^T z over all ranks (NaN/Inf is left to the caller)
  template <class V>
  double step(V* r, double alpha, const V* w, V* x, V* p, double rz, double rz_stop = -1) const;
  /// @return the precision of the transforms
  Precision precision() const { return fft_.precision(); }

private:
  template <class T>
  double solveModes() const;
  Grid grid_;
  double lambda0_, mu0_;
  VectorFft& fft_;
  const Distribution& dist_;
  std::vector<double> sin_[3], cos_[3]; // sin(xi/2), cos(xi/2) per axis
};

} // namespace lamina::homogenize
