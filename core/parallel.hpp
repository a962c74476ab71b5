#pragma once
/// @file parallel.hpp
/// @brief Small helpers for hot loops: the static share of one OpenMP
/// thread, the carrier that takes an exception out of a parallel region,
/// and the attribute that compiles a leaf kernel for several vector widths.
///
/// An exception must not leave an OpenMP region (the runtime calls
/// std::terminate): code inside a region that can throw (a law update, a
/// validation, an allocation) runs through ParallelErrors::run, and the
/// first exception is rethrown after the region.
///
/// LAMINA_VECTOR_CLONES (core/vector_clones.hpp): a leaf kernel compiled
/// for several vector widths.
///
/// ThreadsScope: a solver that picks its own team size sets it for its
/// lifetime and gives the caller's back afterwards.

#include "core/vector_clones.hpp"

#include <omp.h>

#include <atomic>
#include <exception>
#include <utility>

namespace lamina::core {

/// @return [begin, end) of thread @p t's static share of [0, @p n) in a
/// team of @p nt (contiguous shares in thread order).
inline std::pair<int, int> shareRange(int n, int t, int nt) {
  const long ln = n, lt = t, lnt = nt;
  return {static_cast<int>(ln * lt / lnt), static_cast<int>(ln * (lt + 1) / lnt)};
}

/// @return [begin, end) of the calling thread's static share of [0, n)
/// (the whole range outside a parallel region). Contiguous shares keep each
/// thread on the same part of the vectors in every loop of a solve.
inline std::pair<int, int> threadRange(int n) {
  return shareRange(n, omp_get_thread_num(), omp_get_num_threads());
}

/// The first exception thrown inside an OpenMP parallel region, carried out
/// of it. Use:
///
///     core::ParallelErrors errors;
///     #pragma omp parallel for
///     for (...)
///       errors.run([&] { ... });   // may throw
///     errors.rethrow();            // after the region
///
/// Once one call has thrown, later calls skip their work (the region ends
/// soon) but every thread still reaches the region's worksharing constructs
/// and barriers, so a region with several of them stays well formed.
class ParallelErrors {
public:
  /// Runs @p work unless an earlier call failed; keeps the first exception.
  template <class Work>
  void run(Work&& work) noexcept {
    if (failed_.load(std::memory_order_relaxed))
      return;
    try {
      work();
    } catch (...) {
      keep(std::current_exception());
    }
  }
  /// @return whether a call of run() has thrown
  bool failed() const { return failed_.load(std::memory_order_acquire); }
  /// Rethrows the first exception caught, if any (call after the region).
  void rethrow() const {
    if (failed())
      std::rethrow_exception(first_);
  }

private:
  void keep(std::exception_ptr e) noexcept {
#pragma omp critical(lamina_parallel_errors)
    {
      if (!first_)
        first_ = std::move(e);
      failed_.store(true, std::memory_order_release);
    }
  }
  std::exception_ptr first_;
  std::atomic<bool> failed_{false};
};

/// Sets the OpenMP team size (omp_set_num_threads) for the lifetime of the
/// object and restores the previous one when it ends.
class ThreadsScope {
public:
  /// @param threads the team size of the parallel regions in this scope (>= 1)
  explicit ThreadsScope(int threads) { omp_set_num_threads(threads); }
  ~ThreadsScope() { omp_set_num_threads(saved_); }
  ThreadsScope(const ThreadsScope&) = delete;
  ThreadsScope& operator=(const ThreadsScope&) = delete;

private:
  int saved_ = omp_get_max_threads();
};

} // namespace lamina::core
