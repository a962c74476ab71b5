#include "homogenize/cg_solver.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>

namespace lamina::homogenize {

template <class V>
CgSolver<V>::CgSolver(std::size_t local, const CellOperator& A, const GreenOperator& M,
                      const Distribution& dist, double ref_scale)
    : n_(3 * local), A_(A), M_(M), dist_(dist), ref_(ref_scale), r_(n_), p_(n_), w_(n_) {}

// The average stress is linear in the displacement, <C (E + D x)> = <C E>
// + sum_k alpha_k <C D p_k>, and <C D p_k> comes out of the stress pass of
// A p_k, so x is formed only when asked for.
template <class V>
LoadCaseResult CgSolver<V>::solve(const StartResidual& b, const std::array<double, 6>& E,
                                  double energy_E, const Options& opt,
                                  const std::function<void(int, double)>& monitor,
                                  std::array<double, 6>* sigma, V* x) {
  V* r = r_.data();
  V* p = p_.data();
  V* w = w_.data();
  const std::size_t n = n_;
  // r = b = -D^T C' E (x = 0) and <C' E>: the operator's values with u = 0,
  // formed only next to interfaces (start_residual.hpp)
  std::array<double, 6> start{};
  b.apply(E, r, start);
  if (sigma)
    *sigma = start;
  if (x) {
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      x[i] = 0;
  }
  double rz = M_.apply(r, p); // p0 = z0 = M r0, rz = r0^T z0
  const double scale = ref_ * energy_E;
  LoadCaseResult res;
  res.residual = std::sqrt(std::max(rz, 0.0) / scale);
  const std::array<double, 6> zero{0, 0, 0, 0, 0, 0};
  // converged when residual <= tol, i.e. r^T z <= tol^2 scale (the same
  // test decides in step() whether the last inverse transforms are needed)
  const double rz_stop = opt.tol * opt.tol * scale;
  while (rz > rz_stop) {
    if (res.iterations >= opt.max_iterations) {
      std::ostringstream os;
      os << "conjugate gradients did not reach tol " << opt.tol << " in " << opt.max_iterations
         << " iterations (residual " << res.residual << ")";
      throw Error(os.str());
    }
    double pw = 0;
    std::array<double, 6> sigma_p{};
    // w = A p; pw = p^T A p and <C D p> from the stress pass
    A_.apply(p, zero, w, sigma ? &sigma_p : nullptr, &pw);
    const double alpha = rz / pw;
    if (!std::isfinite(alpha) || !(pw > 0))
      throw DivergenceError("conjugate gradients broke down (p^T A p = " + std::to_string(pw) +
                            "): NaN/Inf or an indefinite phase stiffness");
    if (sigma)
      for (std::size_t a = 0; a < 6; ++a)
        (*sigma)[a] += alpha * sigma_p[a];
    // r -= alpha w, x += alpha p, z = M r, p = z + beta p: fused passes
    // (the last step skips the inverse transforms: z would not be used)
    const double rz_new = M_.step(r, alpha, w, x, p, rz, rz_stop);
    if (!std::isfinite(rz_new))
      throw DivergenceError("residual is NaN/Inf in conjugate gradients");
    rz = rz_new;
    ++res.iterations;
    res.residual = std::sqrt(std::max(rz, 0.0) / scale);
    if (monitor)
      monitor(res.iterations, res.residual);
  }
  // With x formed, one stress pass gives <C (E + D x)> directly: the sum of
  // alpha_k <C D p_k> carries the rounding of every step's average (1e-12
  // relative at 128^3, enough to tell thread counts or ranks apart). With
  // single-precision transforms (tol >= 1e-6) that rounding is 5 decades
  // below what the tolerance leaves in C: the pass is skipped.
  if (sigma && x && res.iterations > 0 && std::is_same_v<V, double>)
    A_.apply(x, E, static_cast<V*>(nullptr), sigma);
  return res;
}

template <class V>
void CgSolver<V>::residualDots(const std::vector<AlignedArray<V>>& x, int count,
                               double* dots) const {
  const V* r = r_.data();
  const V* xs[6] = {};
  for (int j = 0; j < count; ++j)
    xs[j] = x[static_cast<std::size_t>(j)].data();
  double d[6] = {0, 0, 0, 0, 0, 0};
#pragma omp parallel for schedule(static) reduction(+ : d[:6])
  for (std::size_t i = 0; i < n_; ++i)
    for (int j = 0; j < count; ++j)
      d[j] += static_cast<double>(xs[j][i]) * static_cast<double>(r[i]);
  for (int j = 0; j < count; ++j)
    dots[j] = d[j];
  dist_.sum(dots, count);
}

template class CgSolver<double>;
template class CgSolver<float>;

} // namespace lamina::homogenize
