#include "membrane/integrators/step_solver.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"

#include <Eigen/SparseCholesky>
#ifdef LAMINA_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace lamina::membrane {

namespace {
/// Below this many rows threads cost more than they save (and a busy core
/// turns every barrier into a scheduler time slice).
constexpr int kParallelMin = 30000;

/// Where the CG finds a node's preconditioner block P.
enum class Blocks {
  Shared,  ///< one 3x3 block, row-major, for every node of a run of shared rows
  PerNode, ///< 3x3 per node, planar: entry (c, d) of node i at (3 c + d) n + i
  Split    ///< in-plane 2x2 block and P(2,2) per node, planar: P00, P01, P10, P11,
           ///< P22 of node i at k n + i, k = 0..4
};

/// z = P r for the node's block at @p m, entry k at m[k s], in the layout
/// @p L. Split blocks skip the exact zeros of the coupling terms (the same
/// numbers).
template <Blocks L>
inline void applyBlock(const double* m, std::ptrdiff_t s, double r0, double r1, double r2,
                       double& z0, double& z1, double& z2) {
  if constexpr (L == Blocks::Split) {
    z0 = m[0] * r0 + m[s] * r1;
    z1 = m[2 * s] * r0 + m[3 * s] * r1;
    z2 = m[4 * s] * r2;
  } else {
    z0 = m[0] * r0 + m[s] * r1 + m[2 * s] * r2;
    z1 = m[3 * s] * r0 + m[4 * s] * r1 + m[5 * s] * r2;
    z2 = m[6 * s] * r0 + m[7 * s] * r1 + m[8 * s] * r2;
  }
}

/// @return the block of node @p i (Blocks::Shared: @p P itself)
template <Blocks L>
inline const double* blockOf(const double* P, int i) {
  if constexpr (L == Blocks::Shared)
    return P;
  return P + i;
}

/// @return the stride between a block's entries: 1 for a shared block, the
/// number of nodes @p n for the planar per-node blocks
template <Blocks L>
inline std::ptrdiff_t blockStride(int n) {
  return L == Blocks::Shared ? 1 : n;
}

/// The CG vector updates on nodes [i0, i1) of planar vectors (plane stride
/// n), with the preconditioner blocks P in the layout L.
/// update: x += alpha p, r -= alpha q, z = P r; adds z.r to rz and r.r to rr.
/// direction: p = P r + beta p (p = P r when beta = 0); adds z.r, r.r the same way.
template <Blocks L>
LAMINA_VECTOR_CLONES void updateNodes(const double* P, int n, double alpha, double* __restrict x,
                                      double* __restrict r, const double* __restrict p,
                                      const double* __restrict q, int i0, int i1, double& rz,
                                      double& rr) {
  const std::ptrdiff_t n1 = n, n2 = 2 * n1, ps = blockStride<L>(n);
  double s = 0, t = 0;
#pragma omp simd reduction(+ : s, t)
  for (int i = i0; i < i1; ++i) {
    const double* m = blockOf<L>(P, i);
    x[i] += alpha * p[i];
    x[n1 + i] += alpha * p[n1 + i];
    x[n2 + i] += alpha * p[n2 + i];
    const double r0 = r[i] - alpha * q[i];
    const double r1 = r[n1 + i] - alpha * q[n1 + i];
    const double r2 = r[n2 + i] - alpha * q[n2 + i];
    r[i] = r0;
    r[n1 + i] = r1;
    r[n2 + i] = r2;
    double z0, z1, z2;
    applyBlock<L>(m, ps, r0, r1, r2, z0, z1, z2);
    s += z0 * r0 + z1 * r1 + z2 * r2;
    t += r0 * r0 + r1 * r1 + r2 * r2;
  }
  rz += s;
  rr += t;
}

template <Blocks L>
LAMINA_VECTOR_CLONES void directionNodes(const double* P, int n, double beta,
                                         const double* __restrict r, double* __restrict p, int i0,
                                         int i1, double& rz, double& rr) {
  const std::ptrdiff_t n1 = n, n2 = 2 * n1, ps = blockStride<L>(n);
  double s = 0, t = 0;
  if (beta == 0) // p may hold anything (NaN) before the first direction
    for (int i = i0; i < i1; ++i)
      p[i] = p[n1 + i] = p[n2 + i] = 0;
#pragma omp simd reduction(+ : s, t)
  for (int i = i0; i < i1; ++i) {
    const double* m = blockOf<L>(P, i);
    const double r0 = r[i], r1 = r[n1 + i], r2 = r[n2 + i];
    double z0, z1, z2;
    applyBlock<L>(m, ps, r0, r1, r2, z0, z1, z2);
    p[i] = z0 + beta * p[i];
    p[n1 + i] = z1 + beta * p[n1 + i];
    p[n2 + i] = z2 + beta * p[n2 + i];
    s += z0 * r0 + z1 * r1 + z2 * r2;
    t += r0 * r0 + r1 * r1 + r2 * r2;
  }
  rz += s;
  rr += t;
}

/// Per-thread partial sums of the CG reductions: two slots used in turn (a
/// slot is rewritten only after a barrier that follows every read of it),
/// one cache line per thread.
struct alignas(64) Partial {
  double v[2][2] = {{0, 0}, {0, 0}};
  bool inplane = false; ///< an in-plane component of x or r not zero on the thread's rows
};
} // namespace

struct StepSolver::Direct {
#ifdef LAMINA_HAVE_CHOLMOD
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
#else
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
#endif
};

StepSolver::StepSolver(const SparseMatrix& A, LinearSolverKind kind, double tolerance,
                       int max_iterations, int projection)
    : kind_(kind), tolerance_(tolerance), max_iterations_(max_iterations), projection_(projection) {
  const int n = static_cast<int>(A.rows());
  if (kind_ == LinearSolverKind::Cholesky) {
    direct_ = std::make_unique<Direct>();
    const Eigen::SparseMatrix<double> Ac = A;
    direct_->llt.compute(Ac);
    if (direct_->llt.info() != Eigen::Success)
      throw Error("sparse Cholesky factorization of A = M + tau^2/2 beta2 K failed "
                  "(matrix not positive definite?)");
    return;
  }
  // Block-Jacobi: invert the 3x3 diagonal block of every node.
  Ab_ = BlockMatrix(A);
  const int nn = n / 3;
  // Shared rows share one inverse (row-major 3x3) per stored row; otherwise
  // one per node in planes (entry k of node i at k nn + i), which the CG's
  // vector loops load like its vectors; split blocks keep the five numbers
  // that are not exact zeros (the cofactors of the coupling terms are
  // differences of products with zeros).
  const bool split = Ab_.splitBlocks(), shared = Ab_.sharedRows() > 0;
  const std::size_t per = split ? 5 : 9;
  block_inverse_.resize(per * static_cast<std::size_t>(Ab_.storedRows()));
  for (int i = 0; i < nn; ++i) {
    const Eigen::Matrix3d inv = Ab_.diagonalBlock(i).inverse();
    const std::ptrdiff_t s = shared ? 1 : nn;
    double* m =
        block_inverse_.data() + (shared ? 9 * static_cast<std::ptrdiff_t>(Ab_.rowOf(i)) : i);
    if (split) {
      // (a singular block gives NaN there as in the 3x3 inverse: not a split failure)
      assert(!inv.allFinite() ||
             (inv(0, 2) == 0 && inv(1, 2) == 0 && inv(2, 0) == 0 && inv(2, 1) == 0));
      m[0] = inv(0, 0);
      m[s] = inv(0, 1);
      m[2 * s] = inv(1, 0);
      m[3 * s] = inv(1, 1);
      m[4 * s] = inv(2, 2);
      continue;
    }
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d)
        m[(3 * c + d) * s] = inv(c, d);
  }
  for (Eigen::VectorXd* v : {&xp_, &rp_, &pp_, &qp_})
    v->resize(n);
  // The normal plane alone (cgThread) needs P r = 0 for r = 0 in the plane:
  // finite in-plane blocks (every inverse finite, A(2,2)'s too).
  normal_plane_ = split && std::all_of(block_inverse_.begin(), block_inverse_.end(),
                                       [](double v) { return std::isfinite(v); });
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

void StepSolver::saveHistory(const std::string& prefix, History& h) const {
  h[prefix + "counts"] =
      Eigen::Vector3d(static_cast<double>(solves_), static_cast<double>(total_iterations_),
                      static_cast<double>(X_.size()));
  for (size_t i = 0; i < X_.size(); ++i) {
    h[prefix + "X/" + std::to_string(i)] = X_[i];
    h[prefix + "AX/" + std::to_string(i)] = AX_[i];
  }
}

void StepSolver::restoreHistory(const std::string& prefix, const History& h) {
  const std::string counts = prefix + "counts";
  constexpr long kMaxCount = 1L << 53; // doubles hold every integer up to here
  solves_ = historyInteger(h, counts, 3, 0, 0, kMaxCount);
  total_iterations_ = historyInteger(h, counts, 3, 1, 0, kMaxCount);
  // the projection basis: at most the vectors the solver keeps
  const auto k = static_cast<size_t>(historyInteger(h, counts, 3, 2, 0, projection_));
  const Eigen::Index n = static_cast<Eigen::Index>(xp_.size());
  X_.resize(k);
  AX_.resize(k);
  for (size_t i = 0; i < k; ++i) {
    X_[i] = historyEntry(h, prefix + "X/" + std::to_string(i), n);
    AX_[i] = historyEntry(h, prefix + "AX/" + std::to_string(i), n);
  }
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

/// One CG solve, shared by the threads of its parallel region.
struct StepSolver::CgRun {
  int nn;                                ///< nodes: the stride of the planar vectors
  double target;                         ///< converged when ||r|| <= target
  Blocks blocks;                         ///< where a node's preconditioner block is
  std::vector<Partial> partial;          ///< per thread: the reductions' partial sums
  CgOutcome outcome = CgOutcome::limit;  ///< thread 0's report, read after the region
  double final_rr = 0;                   ///< r.r at the end
  int iterations = 0;                    ///< iterations done
  BlockPlanes planes = BlockPlanes::All; ///< the planes the products computed
  bool may_skip = false; ///< the normal plane alone allowed (read once, for every thread)
};

/// One thread's share of a CG solve: its nodes [i0, i1) and its partial sums.
struct StepSolver::CgThread {
  CgRun& run;
  int tid, nt, i0, i1;
  BlockPlanes planes = BlockPlanes::All; ///< the planes the products compute
  /// Stores this thread's partial sums z.r and r.r in @p slot.
  void publish(int slot, double rz, double rr) {
    run.partial[tid].v[slot][0] = rz;
    run.partial[tid].v[slot][1] = rr;
  }
  /// Sums slot @p k of every thread's partials, in thread order (the same
  /// result on every thread, so all take the same branch).
  double total(int slot, int k) const {
    double s = 0;
    for (int t = 0; t < nt; ++t)
      s += run.partial[t].v[slot][k];
    return s;
  }
};

void StepSolver::cg(const Eigen::VectorXd& b, Eigen::VectorXd& x, int& iterations,
                    bool have_residual) {
  // Preconditioned CG on planar copies of x, r, p, q inside one parallel
  // region: every thread keeps its static share of the nodes in all loops;
  // three barriers per iteration (after A p, after the update, after the
  // new direction). z = P r is not stored: the update and the direction
  // recompute it from r (a 3x3 product is cheaper than a pass over memory).
  const int n = static_cast<int>(b.size());
  const double bnorm = b.norm();
  last_planes_ = BlockPlanes::All;
  if (!(bnorm > 0)) {
    x.setZero(n);
    return;
  }
  if (x.size() != n)
    x = Eigen::VectorXd::Zero(n);
  const bool parallel = n > kParallelMin;
  const Blocks blocks = Ab_.sharedRows() > 0 ? Blocks::Shared
                        : Ab_.splitBlocks()  ? Blocks::Split
                                             : Blocks::PerNode;
  CgRun run{n / 3, tolerance_ * bnorm, blocks,
            std::vector<Partial>(parallel ? omp_get_max_threads() : 1)};
  run.may_skip = normal_plane_ && BlockMatrix::skipsZeroPlanes();
  const double* r0 = have_residual ? r_.data() : b.data();
#pragma omp parallel if (parallel)
  {
    const auto [i0, i1] = core::threadRange(run.nn);
    CgThread t{run, omp_get_thread_num(), omp_get_num_threads(), i0, i1};
    cgThread(t, r0, have_residual, x);
  }
  iterations = run.iterations;
  last_planes_ = run.planes;
  if (run.outcome == CgOutcome::breakdown)
    throw DivergenceError("CG breakdown: A is not positive definite or the step diverged");
  if (run.outcome == CgOutcome::limit)
    throw DivergenceError("CG did not converge in " + std::to_string(max_iterations_) +
                          " iterations (relative residual " +
                          std::to_string(std::sqrt(run.final_rr) / bnorm) + ")");
}

void StepSolver::cgThread(CgThread& t, const double* r0, bool have_residual, Eigen::VectorXd& x) {
  const int nn = t.run.nn;
  double* xp = xp_.data();
  double* rp = rp_.data();
  double* qp = qp_.data();
  toPlanar(x.data(), xp, nn, t.i0, t.i1);
  toPlanar(r0, rp, nn, t.i0, t.i1);
  const bool may_skip = t.run.may_skip;
  if (may_skip)
    t.run.partial[t.tid].inplane =
        !inPlaneZero(xp, 1, nn, t.i0, t.i1) || !inPlaneZero(rp, 1, nn, t.i0, t.i1);
#pragma omp barrier
  if (may_skip && normalPlaneOnly(t)) {
    // x and r without in-plane part, A without coupling: the in-plane parts
    // of r, P r, p and A p stay zero through the solve (A p's are +0, held
    // in q from here), so the products compute the normal plane alone.
    t.planes = BlockPlanes::Normal;
    std::fill(qp + t.i0, qp + t.i1, 0.0);
    std::fill(qp + nn + t.i0, qp + nn + t.i1, 0.0);
  }
  if (!have_residual) { // r = b - A x (r - (+0) = r in the planes not computed)
    Ab_.multiplyPlanar(xp, qp, t.i0, t.i1, t.planes);
    for (int c = t.planes == BlockPlanes::Normal ? 2 : 0; c < 3; ++c)
      for (int i = t.i0; i < t.i1; ++i)
        rp[c * static_cast<std::ptrdiff_t>(nn) + i] -= qp[c * static_cast<std::ptrdiff_t>(nn) + i];
  }
  double rz_part = 0, rr_part = 0;
  cgDirection(t, 0.0, rz_part, rr_part); // p = z = P r
  t.publish(1, rz_part, rr_part);
#pragma omp barrier
  double rz = t.total(1, 0), rr = t.total(1, 1);
  int it = 0;
  const CgOutcome result =
      std::sqrt(rr) <= t.run.target ? CgOutcome::converged : cgIterate(t, rz, rr, it);
  fromPlanar(xp, x.data(), nn, t.i0, t.i1);
  if (t.tid == 0) {
    t.run.outcome = result;
    t.run.final_rr = rr;
    t.run.iterations = std::min(it, max_iterations_);
    t.run.planes = t.planes;
  }
}

StepSolver::CgOutcome StepSolver::cgIterate(CgThread& t, double rz, double& rr, int& it) {
  for (it = 1; it <= max_iterations_; ++it) {
    t.run.partial[t.tid].v[0][0] =
        Ab_.multiplyPlanar(pp_.data(), qp_.data(), t.i0, t.i1, t.planes); // q = A p, p.q
#pragma omp barrier
    const double pq = t.total(0, 0);
    if (!(pq > 0) || !std::isfinite(pq))
      return CgOutcome::breakdown;
    const double alpha = rz / pq;
    double rz_part = 0, rr_part = 0;
    cgUpdate(t, alpha, rz_part, rr_part);
    t.publish(1, rz_part, rr_part);
#pragma omp barrier
    const double rz_new = t.total(1, 0);
    rr = t.total(1, 1);
    if (std::sqrt(rr) <= t.run.target)
      return CgOutcome::converged;
    const double beta = rz_new / rz;
    rz = rz_new;
    rz_part = rr_part = 0;
    cgDirection(t, beta, rz_part, rr_part); // its sums repeat the update's: unused
#pragma omp barrier
  }
  return CgOutcome::limit;
}

bool StepSolver::normalPlaneOnly(const CgThread& t) const {
  for (int k = 0; k < t.nt; ++k)
    if (t.run.partial[k].inplane)
      return false;
  return true;
}

void StepSolver::cgUpdate(const CgThread& t, double alpha, double& rz, double& rr) {
  const double* P = block_inverse_.data();
  const int nn = t.run.nn;
  double* xp = xp_.data();
  double* rp = rp_.data();
  const double* pp = pp_.data();
  const double* qp = qp_.data();
  if (t.run.blocks == Blocks::Split)
    return updateNodes<Blocks::Split>(P, nn, alpha, xp, rp, pp, qp, t.i0, t.i1, rz, rr);
  if (t.run.blocks == Blocks::PerNode)
    return updateNodes<Blocks::PerNode>(P, nn, alpha, xp, rp, pp, qp, t.i0, t.i1, rz, rr);
  Ab_.forEachRun(t.i0, t.i1, [&](int r0, int r1, int row) {
    updateNodes<Blocks::Shared>(P + 9 * static_cast<std::ptrdiff_t>(row), nn, alpha, xp, rp, pp, qp,
                                r0, r1, rz, rr);
  });
}

void StepSolver::cgDirection(const CgThread& t, double beta, double& rz, double& rr) {
  const double* P = block_inverse_.data();
  const int nn = t.run.nn;
  const double* rp = rp_.data();
  double* pp = pp_.data();
  if (t.run.blocks == Blocks::Split)
    return directionNodes<Blocks::Split>(P, nn, beta, rp, pp, t.i0, t.i1, rz, rr);
  if (t.run.blocks == Blocks::PerNode)
    return directionNodes<Blocks::PerNode>(P, nn, beta, rp, pp, t.i0, t.i1, rz, rr);
  Ab_.forEachRun(t.i0, t.i1, [&](int r0, int r1, int row) {
    directionNodes<Blocks::Shared>(P + 9 * static_cast<std::ptrdiff_t>(row), nn, beta, rp, pp, r0,
                                   r1, rz, rr);
  });
}

} // namespace lamina::membrane
