#pragma once
/// @file cg_solver.hpp
/// @brief The linear cell problem solved by the conjugate-gradient loop
/// (conjugate_gradients.hpp), for any right-hand side a StartResidual
/// forms: the six macro load cases of the Homogenizer (b = -D^T C E) and
/// the eigenstrain influence functions of a reduced-order cell (reduced_order_builder.hpp:
/// b = D^T L0 mu N^(alpha), the same -D^T C' E with E = -mu and a stiffness
/// list C' that is L0 inside partition alpha and zero elsewhere).
///
/// Method: A x = b with A = D^T C D (cell_operator.hpp), x = 0 to start,
/// preconditioned by the reference-medium Green operator M
/// (green_operator.hpp), whose r^T z is the residual in the reference energy
/// norm. Convergence: sqrt(r^T z / (ref_scale E^T C0 E)) <= tol, i.e. the
/// error of the strain field in the reference energy norm relative to the
/// strain E applied over the whole cell. The fields are this rank's slab;
/// the sums over the grid and the CG scalars are double. V: the type of the
/// CG vectors and of the operator's arithmetic (float or double).

#include "homogenize/cell_operator.hpp"
#include "homogenize/conjugate_gradients.hpp"
#include "homogenize/distribution.hpp"
#include "homogenize/green_operator.hpp"
#include "homogenize/grid.hpp"
#include "homogenize/start_residual.hpp"

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace lamina::homogenize {

/// The pieces of one solve, set up once and reused by every right-hand side:
/// the operator, the preconditioner and the three CG vectors r, p, w (z is
/// fused into p by GreenOperator::step).
template <class V>
class CgSolver {
public:
  /// @param local nodes of this rank's slab (dist.localSize())
  /// @param A the cell operator; @param M the preconditioner; @param dist
  /// the distribution of the fields (all must outlive the solver)
  /// @param ref_scale the number of voxels of the whole grid (the scale of
  /// the convergence test)
  CgSolver(std::size_t local, const CellOperator& A, const GreenOperator& M,
           const Distribution& dist, double ref_scale);

  /// Solves A x = b with b = -D^T C' E formed by @p b (whose stiffness list
  /// C' may differ from A's: see the file comment).
  /// @param energy_E E^T C0 E, the scale of the convergence test
  /// @param tol relative residual to reach; @param max_iterations limit
  /// @param monitor called after each iteration with (iteration, residual)
  /// @param sigma if not null: on exit the average stress <C (E + D x)> of
  ///   A's stiffness (meaningful when C' is A's list; a macro load case)
  /// @param x if not null: on exit the displacement (3 x local)
  /// @return iterations and final residual. Throws lamina::Error when
  /// max_iterations is reached, lamina::DivergenceError on NaN/Inf.
  CgResult solve(const StartResidual& b, const std::array<double, 6>& E, double energy_E,
                 double tol, int max_iterations, const std::function<void(int, double)>& monitor,
                 std::array<double, 6>* sigma, V* x);

  /// dots[j] = x_j^T r (r: the last solve's final residual), j < count <= 6,
  /// summed over ranks, in one pass over r.
  void residualDots(const std::vector<AlignedArray<V>>& x, int count, double* dots) const;

private:
  std::size_t n_;
  const CellOperator& A_;
  const GreenOperator& M_;
  const Distribution& dist_;
  double ref_;
  AlignedArray<V> r_, p_, w_;
};

extern template class CgSolver<double>;
extern template class CgSolver<float>;

} // namespace lamina::homogenize
