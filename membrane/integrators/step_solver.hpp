#pragma once
/// @file step_solver.hpp
/// @brief Solves A x = b for the constant Newmark matrix A = M + tau^2/2 beta2 K
/// (constrained rows and columns already replaced by the identity).
///
/// Contract: the matrix is set up once (constructor) and reused for every
/// step. "cg": conjugate gradients preconditioned by the inverse 3x3 node
/// blocks of A, warm-started from the x passed in, stopped when
/// ||b - A x|| <= tolerance ||b||. The iteration runs on planar copies of
/// its vectors (BlockMatrix) in one OpenMP region for matrices above 30,000
/// rows. When A has split blocks (no coupling of the in-plane and normal
/// components) and the in-plane parts of the start and of its residual
/// (b, or the projection's) are zero (the linear membrane under transverse
/// load), the in-plane parts stay zero
/// through the iteration and its products compute the normal plane alone
/// (BlockPlanes::Normal): the same bits as the full products. "cholesky": a
/// sparse Cholesky factorization (CHOLMOD supernodal when built with it,
/// else Eigen's SimplicialLDLT), exact to round-off.
///
/// The CG start: when @p projection > 0, the initial guess is the A-orthogonal
/// projection of the solution on the span of the last solutions (Fischer,
/// "Projection techniques for iterative solution of Ax = b with successive
/// right-hand sides", 1998): the best combination of past steps in the A
/// norm, which contains any polynomial extrapolation of them.

#include "membrane/integrators/time_integrator.hpp"
#include "membrane/model/assembly.hpp"
#include "membrane/model/block_matrix.hpp"
#include "membrane/system/model.hpp"

#include <Eigen/Dense>

#include <memory>
#include <string>

namespace lamina::membrane {

/// Linear solver of one Newmark step.
class StepSolver {
public:
  /// Sets up the solver for @p A (symmetric positive definite, 3x3 block
  /// pattern) with the method @p kind. A is copied (blocks) or factorized:
  /// it need not outlive the solver.
  StepSolver(const SparseMatrix& A, LinearSolverKind kind, double tolerance, int max_iterations,
             int projection = 0);
  ~StepSolver();
  StepSolver(const StepSolver&) = delete;
  StepSolver& operator=(const StepSolver&) = delete;

  /// Solves A x = b; @p x holds the initial guess on entry (cg) and the
  /// solution on exit. @return the number of iterations (1 for cholesky).
  /// Throws lamina::DivergenceError when CG does not reach the tolerance.
  int solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  /// @return total iterations over all solves
  long totalIterations() const { return total_iterations_; }
  /// @return number of solves
  long solves() const { return solves_; }
  /// @return the planes the products of the last CG solve computed
  /// (BlockPlanes::Normal: the normal plane alone, see the file comment)
  BlockPlanes lastPlanes() const { return last_planes_; }
  /// Saves the counters and the projection basis (what later solves depend
  /// on) into @p h under keys starting with @p prefix.
  void saveHistory(const std::string& prefix, History& h) const;
  /// Restores what saveHistory() wrote; throws lamina::Error on a missing
  /// or mis-sized entry.
  void restoreHistory(const std::string& prefix, const History& h);

private:
  /// How a CG solve ended.
  enum class CgOutcome { converged, breakdown, limit };
  struct CgRun;    // one CG solve, shared by the threads of its parallel region
  struct CgThread; // one thread's share of a solve: its nodes and partial sums
  /// CG from @p x (r = b - A x, or r_ when @p have_residual); throws
  /// lamina::DivergenceError on a breakdown or at the iteration limit.
  void cg(const Eigen::VectorXd& b, Eigen::VectorXd& x, int& iterations, bool have_residual);
  /// One thread's CG: planar copies, start residual (from @p r0, b or r_),
  /// first direction, iterations, x back; thread 0 reports in t.run.
  void cgThread(CgThread& t, const double* r0, bool have_residual, Eigen::VectorXd& x);
  /// The iterations from p = P r (z.r = @p rz, r.r = @p rr); @p it counts them.
  CgOutcome cgIterate(CgThread& t, double rz, double& rr, int& it);
  /// x += alpha p, r -= alpha q on the thread's nodes; adds z.r, r.r to @p rz, @p rr.
  void cgUpdate(const CgThread& t, double alpha, double& rz, double& rr);
  /// p = P r + beta p on the thread's nodes; adds z.r, r.r to @p rz, @p rr.
  void cgDirection(const CgThread& t, double beta, double& rz, double& rr);
  /// @return true when no thread found an in-plane component of x or r not
  /// zero (read after the barrier that follows the threads' checks)
  bool normalPlaneOnly(const CgThread& t) const;
  void project(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  void remember(const Eigen::VectorXd& x);
  BlockMatrix Ab_; // the same matrix in 3x3 blocks, for the CG products
  LinearSolverKind kind_;
  double tolerance_;
  int max_iterations_;
  std::vector<double> block_inverse_; // block-Jacobi: 9 per shared row (row-major), else 9 or
                                      // 5 (split) planes of one entry per node
  int projection_ = 0;                // max basis size (0 = off)
  BlockPlanes last_planes_ = BlockPlanes::All;
  bool normal_plane_ = false;           // split blocks with finite inverses: the CG may
                                        // run on the normal plane alone
  std::vector<Eigen::VectorXd> X_, AX_; // A-orthonormal past solutions and A X
  Eigen::VectorXd x0_, d_, ad_, r_;     // projection: start, new direction, A d, residual
  Eigen::VectorXd xp_, rp_, pp_, qp_;   // CG vectors, planar (component c of node i at c n + i)
  struct Direct;
  std::unique_ptr<Direct> direct_;
  long total_iterations_ = 0, solves_ = 0;
};

} // namespace lamina::membrane
