#include "membrane/integrators/step_solver.hpp"

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
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      s += val[k] * xp[inner[k]];
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
                       int max_iterations, int projection)
    : kind_(kind), tolerance_(tolerance), max_iterations_(max_iterations), projection_(projection) {
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
  Ab_ = BlockMatrix(A);
  const int nn = n / 3;
  // One inverse per stored row: shared rows share their inverse too (fewer bytes per iteration).
  block_inverse_.resize(Ab_.sharedRows() > 0 ? Ab_.sharedRows() : nn);
  for (int i = 0; i < nn; ++i)
    block_inverse_[Ab_.rowOf(i)] = Ab_.diagonalBlock(i).inverse();
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
  const bool projected = projection_ > 0 && !X_.empty();
  if (projected)
    project(b, x); // x and r_ from the basis, no SpMV
  cg(b, x, it, projected);
  if (projection_ > 0)
    remember(x);
  total_iterations_ += it;
  return it;
}

void StepSolver::project(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  // x0 = sum (X_i . b) X_i minimizes the A-norm error over span(X); r0 = b - A x0.
  x.setZero(b.size());
  r_ = b;
  for (size_t i = 0; i < X_.size(); ++i) {
    const double c = X_[i].dot(b);
    x += c * X_[i];
    r_ -= c * AX_[i];
  }
  x0_ = x;
}

void StepSolver::remember(const Eigen::VectorXd& x) {
  // Add the new direction d = x - x0 (A-orthonormalized) to the basis; when
  // full, restart the basis from the current solution alone.
  if (static_cast<int>(X_.size()) >= projection_) {
    X_.clear();
    AX_.clear();
    d_ = x;
  } else {
    d_ = X_.empty() ? x : Eigen::VectorXd(x - x0_);
  }
  Ab_.multiply(d_, ad_);
  for (int pass = 0; pass < 2; ++pass) // twice is enough (Kahan)
    for (size_t i = 0; i < X_.size(); ++i) {
      const double c = AX_[i].dot(d_);
      d_ -= c * X_[i];
      ad_ -= c * AX_[i];
    }
  const double nrm2 = d_.dot(ad_);
  if (!(nrm2 > 0) || !std::isfinite(nrm2))
    return;
  const double s = 1 / std::sqrt(nrm2);
  X_.push_back(s * d_);
  AX_.push_back(s * ad_);
}

void StepSolver::cg(const Eigen::VectorXd& b, Eigen::VectorXd& x, int& iterations,
                    bool have_residual) {
  const int n = static_cast<int>(b.size());
  const int nn = n / 3;
  const double bnorm = b.norm();
  if (!(bnorm > 0)) {
    x.setZero(n);
    return;
  }
  if (x.size() != n)
    x = Eigen::VectorXd::Zero(n);
  if (!have_residual) {
    Ab_.multiply(x, q_);
    r_ = b - q_;
  }
  const double target = tolerance_ * bnorm;
  double rr = r_.squaredNorm();
  if (std::sqrt(rr) <= target)
    return;
  double rz = 0;
#pragma omp parallel for reduction(+ : rz) schedule(static) if (n > kParallelMin)
  for (int i = 0; i < nn; ++i) {
    z_.segment<3>(3 * i) = block_inverse_[Ab_.rowOf(i)] * r_.segment<3>(3 * i);
    rz += z_.segment<3>(3 * i).dot(r_.segment<3>(3 * i));
  }
  p_ = z_;
  for (iterations = 1; iterations <= max_iterations_; ++iterations) {
    const double pq = Ab_.multiplyDot(p_, q_);
    if (!(pq > 0) || !std::isfinite(pq))
      throw DivergenceError("CG breakdown: A is not positive definite or the step diverged");
    const double alpha = rz / pq;
    double rz_new = 0;
    rr = 0;
#pragma omp parallel for reduction(+ : rz_new, rr) schedule(static) if (n > kParallelMin)
    for (int i = 0; i < nn; ++i) {
      x.segment<3>(3 * i) += alpha * p_.segment<3>(3 * i);
      r_.segment<3>(3 * i) -= alpha * q_.segment<3>(3 * i);
      z_.segment<3>(3 * i) = block_inverse_[Ab_.rowOf(i)] * r_.segment<3>(3 * i);
      rz_new += z_.segment<3>(3 * i).dot(r_.segment<3>(3 * i));
      rr += r_.segment<3>(3 * i).squaredNorm();
    }
    if (std::sqrt(rr) <= target)
      return;
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (int i = 0; i < n; ++i)
      p_[i] = z_[i] + beta * p_[i];
  }
  throw DivergenceError("CG did not converge in " + std::to_string(max_iterations_) +
                        " iterations (relative residual " + std::to_string(std::sqrt(rr) / bnorm) +
                        ")");
}

} // namespace lamina::membrane
