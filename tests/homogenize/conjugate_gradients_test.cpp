// The conjugate-gradient loop of homogenize (homogenize/conjugate_gradients.hpp)
// on small dense systems whose behaviour is known in exact arithmetic:
// - CG ends in at most as many iterations as the right-hand side has
//   distinct eigenvalue components (Saad, "Iterative Methods for Sparse
//   Linear Systems", 2nd ed., Sec. 6.11.3: the error lies in a Krylov space
//   of that dimension). The 1D Laplacian tridiag(-1, 2, -1) of order n = 10
//   has 10 distinct eigenvalues, but b = 1 is symmetric about the middle, so
//   only the 5 symmetric eigenvectors take part: at most 5 iterations.
// - with the exact inverse as preconditioner one iteration solves it (z is
//   the solution direction, alpha = 1).
// - the failures: max_iterations reached (lamina::Error) and an operator
//   with p^T A p <= 0 (lamina::DivergenceError naming the problem's cause).
#include "core/error.hpp"
#include "homogenize/conjugate_gradients.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

using lamina::homogenize::CgControl;
using lamina::homogenize::CgProblem;
using lamina::homogenize::conjugateGradients;

/// A x = b with a dense A and a diagonal preconditioner M = diag(m).
class DenseProblem final : public CgProblem {
public:
  DenseProblem(std::vector<std::vector<double>> A, std::vector<double> m, std::vector<double> b)
      : x(b.size()), A_(std::move(A)), m_(std::move(m)), r_(std::move(b)), n_(r_.size()),
        z_(n_), p_(n_), w_(n_) {}

  std::vector<double> x; ///< the solution

  double start() override {
    std::fill(x.begin(), x.end(), 0.0);
    const double rz = precondition();
    p_ = z_;
    return rz;
  }
  double applyToDirection() override {
    double pw = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      w_[i] = 0;
      for (std::size_t j = 0; j < n_; ++j)
        w_[i] += A_[i][j] * p_[j];
      pw += p_[i] * w_[i];
    }
    return pw;
  }
  double update(double alpha, double rz, double) override {
    for (std::size_t i = 0; i < n_; ++i) {
      x[i] += alpha * p_[i];
      r_[i] -= alpha * w_[i];
    }
    const double rz_new = precondition();
    for (std::size_t i = 0; i < n_; ++i)
      p_[i] = z_[i] + rz_new / rz * p_[i];
    return rz_new;
  }
  const char* indefiniteCause() const override { return "a test operator"; }

private:
  double precondition() {
    double rz = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      z_[i] = m_[i] * r_[i];
      rz += r_[i] * z_[i];
    }
    return rz;
  }
  std::vector<std::vector<double>> A_;
  std::vector<double> m_, r_;
  std::size_t n_;
  std::vector<double> z_, p_, w_;
};

std::vector<std::vector<double>> laplacian(std::size_t n) {
  std::vector<std::vector<double>> A(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    A[i][i] = 2;
    if (i > 0)
      A[i][i - 1] = A[i - 1][i] = -1;
  }
  return A;
}

TEST(ConjugateGradients, EndsInAtMostFiveIterationsOnTheSymmetricLaplacianProblem) {
  const std::size_t n = 10;
  std::vector<double> b(n, 1.0);
  DenseProblem problem(laplacian(n), std::vector<double>(n, 1.0), b);
  int calls = 0;
  const auto res = conjugateGradients(problem, CgControl::relative(1e-10, 1.0, 100),
                                      [&](int it, double) { EXPECT_EQ(it, ++calls); });
  EXPECT_LE(res.iterations, 5); // the 5 symmetric eigencomponents of b
  EXPECT_EQ(calls, res.iterations);
  EXPECT_LE(res.residual, 1e-10);
  // exact solution of tridiag(-1, 2, -1) x = 1: x_i = (i + 1)(n - i) / 2 (up
  // to 15). After finite termination the error is rounding (about 1e-14 here,
  // cond(A) = 48); 1e-9 is far above it and far below any wrong answer.
  for (std::size_t i = 0; i < n; ++i)
    EXPECT_NEAR(problem.x[i], 0.5 * static_cast<double>((i + 1) * (n - i)), 1e-9) << i;
}

TEST(ConjugateGradients, ExactPreconditionerSolvesInOneIteration) {
  const std::vector<double> d{1, 4, 9, 100};
  std::vector<std::vector<double>> A(4, std::vector<double>(4, 0.0));
  std::vector<double> m(4);
  for (std::size_t i = 0; i < 4; ++i) {
    A[i][i] = d[i];
    m[i] = 1 / d[i];
  }
  DenseProblem problem(A, m, {1, 1, 1, 1});
  const auto res = conjugateGradients(problem, CgControl::relative(1e-12, 1.0, 10));
  EXPECT_EQ(res.iterations, 1);
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(problem.x[i], 1 / d[i], 1e-15);
}

TEST(ConjugateGradients, MaxIterationsIsAnError) {
  DenseProblem problem(laplacian(10), std::vector<double>(10, 1.0), std::vector<double>(10, 1.0));
  try {
    conjugateGradients(problem, CgControl::relative(1e-10, 1.0, 2));
    FAIL() << "no error";
  } catch (const lamina::DivergenceError&) {
    FAIL() << "a DivergenceError for an unconverged solve";
  } catch (const lamina::Error& e) {
    EXPECT_NE(std::string(e.what()).find("did not reach tol 1e-10 in 2 iterations"),
              std::string::npos)
        << e.what();
  }
}

TEST(ConjugateGradients, IndefiniteOperatorIsADivergence) {
  std::vector<std::vector<double>> A{{-1, 0}, {0, -2}};
  DenseProblem problem(A, {1, 1}, {1, 1});
  try {
    conjugateGradients(problem, CgControl::relative(1e-10, 1.0, 10));
    FAIL() << "no error";
  } catch (const lamina::DivergenceError& e) {
    EXPECT_NE(std::string(e.what()).find("broke down"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a test operator"), std::string::npos) << e.what();
  }
}

TEST(ConjugateGradients, AbsoluteStopIsOnTheNormOfTheResidual) {
  // stop = sqrt(r^T z) <= 2: with b = (3) and M = 1, r^T z = 9 > 4 at the
  // start and 0 after one iteration of A = (1)
  DenseProblem problem({{1}}, {1}, {3});
  const auto res = conjugateGradients(problem, CgControl::absolute(2, 9, 10));
  EXPECT_EQ(res.iterations, 1);
  DenseProblem done({{1}}, {1}, {1.5});
  EXPECT_EQ(conjugateGradients(done, CgControl::absolute(2, 9, 10)).iterations, 0);
}

} // namespace
