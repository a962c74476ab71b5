#include "membrane/step_solver.hpp"

#include "core/error.hpp"

#include <Eigen/SparseCholesky>
#ifdef LAMINA_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <cmath>

namespace lamina::membrane {

namespace {
/// Below this many rows threads cost more than they save (and a busy core
/// turns every barrier into a scheduler time slice).
constexpr int kParallelMin = 30000;
} // namespace

void multiply(const SparseMatrix& A, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const int n = static_cast<int>(A.rows());
  y.resize(n);
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* val = A.valuePtr();
  const double* xp = x.data();
  double* yp = y.data();
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) s += val[k] * xp[inner[k]];
    yp[i] = s;
  }
}

struct StepSolver::Direct {
#ifdef LAMINA_HAVE_CHOLMOD
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
#else
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
#endif
};

StepSolver::StepSolver(const SparseMatrix& A, const std::string& kind, double tolerance,
                       int max_iterations)
    : A_(A), kind_(kind), tolerance_(tolerance), max_iterations_(max_iterations) {
  const int n = static_cast<int>(A.rows());
  if (kind_ == "cholesky") {
    direct_ = std::make_unique<Direct>();
    const Eigen::SparseMatrix<double> Ac = A;
    direct_->llt.compute(Ac);
    if (direct_->llt.info() != Eigen::Success)
      throw Error("sparse Cholesky factorization of A = M + tau^2/2 beta2 K failed "
                  "(matrix not positive definite?)");
    return;
  }
  LAMINA_CHECK(kind_ == "cg", "unknown solver '", kind_, "'");
  // Block-Jacobi: invert the 3x3 diagonal block of every node.
  const int nn = n / 3;
  block_inverse_.resize(nn);
  for (int i = 0; i < nn; ++i) {
    Eigen::Matrix3d B = Eigen::Matrix3d::Zero();
    for (int c = 0; c < 3; ++c)
      for (SparseMatrix::InnerIterator it(A, 3 * i + c); it; ++it)
        if (it.col() / 3 == i) B(c, it.col() % 3) = it.value();
    block_inverse_[i] = B.inverse();
  }
  r_.resize(n);
  z_.resize(n);
  p_.resize(n);
  q_.resize(n);
}

StepSolver::~StepSolver() = default;

int StepSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  ++solves_;
  if (direct_) {
    x = direct_->llt.solve(b);
    ++total_iterations_;
    return 1;
  }
  int it = 0;
  cg(b, x, it);
  total_iterations_ += it;
  return it;
}

void StepSolver::cg(const Eigen::VectorXd& b, Eigen::VectorXd& x, int& iterations) {
  const int n = static_cast<int>(b.size());
  const int nn = n / 3;
  const double bnorm = b.norm();
  if (!(bnorm > 0)) {
    x.setZero();
    return;
  }
  if (x.size() != n) x = Eigen::VectorXd::Zero(n);
  multiply(A_, x, q_);
  r_ = b - q_;
  const double target = tolerance_ * bnorm;
  double rr = r_.squaredNorm();
  if (std::sqrt(rr) <= target) return;
  double rz = 0;
#pragma omp parallel for reduction(+ : rz) schedule(static) if (n > kParallelMin)
  for (int i = 0; i < nn; ++i) {
    z_.segment<3>(3 * i) = block_inverse_[i] * r_.segment<3>(3 * i);
    rz += z_.segment<3>(3 * i).dot(r_.segment<3>(3 * i));
  }
  p_ = z_;
  for (iterations = 1; iterations <= max_iterations_; ++iterations) {
    multiply(A_, p_, q_);
    const double pq = p_.dot(q_);
    if (!(pq > 0) || !std::isfinite(pq))
      throw DivergenceError("CG breakdown: A is not positive definite or the step diverged");
    const double alpha = rz / pq;
    double rz_new = 0;
    rr = 0;
#pragma omp parallel for reduction(+ : rz_new, rr) schedule(static) if (n > kParallelMin)
    for (int i = 0; i < nn; ++i) {
      x.segment<3>(3 * i) += alpha * p_.segment<3>(3 * i);
      r_.segment<3>(3 * i) -= alpha * q_.segment<3>(3 * i);
      z_.segment<3>(3 * i) = block_inverse_[i] * r_.segment<3>(3 * i);
      rz_new += z_.segment<3>(3 * i).dot(r_.segment<3>(3 * i));
      rr += r_.segment<3>(3 * i).squaredNorm();
    }
    if (std::sqrt(rr) <= target) return;
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (int i = 0; i < n; ++i) p_[i] = z_[i] + beta * p_[i];
  }
  throw DivergenceError("CG did not converge in " + std::to_string(max_iterations_) +
                        " iterations (relative residual " +
                        std::to_string(std::sqrt(rr) / bnorm) + ")");
}

} // namespace lamina::membrane
