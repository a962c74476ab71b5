#include "homogenize/cg_solver.hpp"

#include "homogenize/conjugate_gradients.hpp"

#include <type_traits>

namespace lamina::homogenize {

template <class V>
CgSolver<V>::CgSolver(std::size_t local, const CellOperator& A, const GreenOperator& M,
                      const Distribution& dist, double ref_scale)
    : n_(3 * local), A_(A), M_(M), dist_(dist), ref_(ref_scale), r_(n_), p_(n_), w_(n_) {}

namespace {

// The linear cell problem for the loop (conjugate_gradients.hpp): r = b is
// formed by the caller; w = A p in one pass that also gives p^T A p and
// <C D p>, and the update fused around the preconditioner's transforms.
// The average stress is linear in the displacement, <C (E + D x)> = <C E>
// + sum_k alpha_k <C D p_k>, and <C D p_k> comes out of the stress pass of
// A p_k, so x is formed only when asked for.
template <class V>
class CellProblem final : public CgProblem {
public:
  CellProblem(const CellOperator& A, const GreenOperator& M, std::size_t n, V* r, V* p, V* w, V* x,
              std::array<double, 6>* sigma)
      : A_(A), M_(M), n_(n), r_(r), p_(p), w_(w), x_(x), sigma_(sigma) {}

  double start() override {
    if (x_) {
      V* x = x_;
      const std::size_t n = n_;
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        x[i] = 0;
    }
    return M_.apply(r_, p_); // p0 = z0 = M r0, rz = r0^T z0
  }

  double applyToDirection() override {
    double pw = 0;
    sigma_p_ = {};
    // w = A p; pw = p^T A p and <C D p> from the stress pass
    A_.apply(p_, kZero, w_, sigma_ ? &sigma_p_ : nullptr, &pw);
    return pw;
  }

  double update(double alpha, double rz, double rz_stop) override {
    if (sigma_)
      for (std::size_t a = 0; a < 6; ++a)
        (*sigma_)[a] += alpha * sigma_p_[a];
    // r -= alpha w, x += alpha p, z = M r, p = z + beta p: fused passes
    // (the last step skips the inverse transforms: z would not be used)
    return M_.step(r_, alpha, w_, x_, p_, rz, rz_stop);
  }

  const char* indefiniteCause() const override {
    return "an indefinite phase stiffness";
  }

private:
  static constexpr std::array<double, 6> kZero{0, 0, 0, 0, 0, 0};
  const CellOperator& A_;
  const GreenOperator& M_;
  std::size_t n_;
  V *r_, *p_, *w_, *x_;
  std::array<double, 6>* sigma_;
  std::array<double, 6> sigma_p_{};
};

} // namespace

template <class V>
CgResult CgSolver<V>::solve(const StartResidual& b, const std::array<double, 6>& E, double energy_E,
                            double tol, int max_iterations,
                            const std::function<void(int, double)>& monitor,
                            std::array<double, 6>* sigma, V* x) {
  // r = b = -D^T C' E (x = 0) and <C' E>: the operator's values with u = 0,
  // formed only next to interfaces (start_residual.hpp)
  std::array<double, 6> start{};
  b.apply(E, r_.data(), start);
  if (sigma)
    *sigma = start;
  CellProblem<V> problem(A_, M_, n_, r_.data(), p_.data(), w_.data(), x, sigma);
  const CgResult res = conjugateGradients(
      problem, CgControl::relative(tol, ref_ * energy_E, max_iterations), monitor);
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
