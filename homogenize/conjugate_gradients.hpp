#pragma once
/// @file conjugate_gradients.hpp
/// @brief The one preconditioned conjugate-gradient loop of homogenize, for
/// any symmetric positive (semi-)definite system behind a small operator
/// interface: the linear cell problem (cg_solver.hpp: the Homogenizer's six
/// load cases and the reduced-order influence functions) and the Newton
/// systems of the nonlinear cell (nonlinear_homogenizer.cpp).
///
/// Method (Saad, "Iterative Methods for Sparse Linear Systems", 2nd ed.,
/// Algorithm 9.1): from x = 0, r = b, z = M r, p = z, repeat
///     w = A p,  alpha = r^T z / p^T w,  x += alpha p,  r -= alpha w,
///     z = M r,  p = z + (r^T z)_new / (r^T z) p
/// until r^T z <= rz_stop. The problem (CgProblem) owns the vectors and does
/// the passes over them, so it may fuse them (the linear cell problem does
/// r -= alpha w inside the forward transform of M); the loop owns the
/// scalars, the convergence test, the failure checks and the reporting.
///
/// Contract: r^T z is the squared residual in the norm of M, so the
/// reported residual is sqrt(max(r^T z, 0) / scale) with the problem's
/// scale (relative to the applied load). Failures: lamina::Error when
/// max_iterations is reached before convergence; lamina::DivergenceError
/// when p^T A p is not positive or not finite (NaN/Inf, or an operator that
/// is not positive definite) or r^T z is not finite; lamina::Interrupted
/// (core::throwIfInterrupted) before an iteration when an interrupt was
/// requested (an InterruptGuard's signal: the Python module's Ctrl-C).

#include <functional>

namespace lamina::homogenize {

/// Iterations and final residual of one conjugate-gradient solve.
struct CgResult {
  int iterations = 0;  ///< CG iterations
  double residual = 0; ///< final relative residual, sqrt(r^T z / scale)
};

/// When conjugate gradients stop, and how their residual is reported.
struct CgControl {
  double scale = 1;       ///< the residual reported is sqrt(max(r^T z, 0) / scale)
  double rz_stop = 0;     ///< converged when r^T z <= rz_stop
  double tol = 0;         ///< the relative residual rz_stop stands for (messages)
  int max_iterations = 0; ///< reaching it unconverged is an error

  /// Stop at relative residual @p tol: rz_stop = tol^2 scale.
  static CgControl relative(double tol, double scale, int max_iterations);
  /// Stop when sqrt(r^T z) <= @p stop (rz_stop = stop^2); the residual is
  /// reported relative to sqrt(@p scale).
  static CgControl absolute(double stop, double scale, int max_iterations);
};

/// The vectors and passes of one conjugate-gradient solve: the operator A,
/// the preconditioner M, and x, r, z, p, w, owned by the implementation.
class CgProblem {
public:
  virtual ~CgProblem() = default;
  /// x = 0, z = M r, p = z for the right-hand side r = b the problem holds.
  /// @return r^T z (summed over ranks)
  virtual double start() = 0;
  /// w = A p. @return p^T w (summed over ranks)
  virtual double applyToDirection() = 0;
  /// x += alpha p, r -= alpha w, z = M r and p = z + (r^T z / @p rz) p.
  /// When the new r^T z is at most @p rz_stop CG stops and does not use z
  /// or p again: they may be left unformed.
  /// @return the new r^T z (summed over ranks; NaN/Inf is left to the loop)
  virtual double update(double alpha, double rz, double rz_stop) = 0;
  /// @return what a p^T A p that is not positive means for this operator
  /// (ends "NaN/Inf or ...")
  virtual const char* indefiniteCause() const = 0;
};

/// Solves the system of @p problem by preconditioned conjugate gradients.
/// @param monitor if set, called after each iteration with (iteration, residual)
/// @return iterations and final residual. Throws as the file comment says.
CgResult conjugateGradients(CgProblem& problem, const CgControl& control,
                            const std::function<void(int, double)>& monitor = {});

} // namespace lamina::homogenize
