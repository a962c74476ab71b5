#pragma once
/// @file parallel.hpp
/// @brief Small helpers for hot loops: the static share of one OpenMP
/// thread, and the attribute that compiles a leaf kernel for several vector
/// widths.
///
/// LAMINA_VECTOR_CLONES: the build targets baseline x86-64 (SSE2, no FMA),
/// which runs anywhere; a function carrying this attribute is compiled three
/// times (x86-64-v4 = AVX-512, x86-64-v3 = AVX2 + FMA, baseline) and the
/// loader picks the widest the CPU has (GCC function multi-versioning).
/// Put it only on leaf functions without OpenMP pragmas (GCC outlines the
/// body of a parallel region before cloning, so the clones would not reach
/// it). Other compilers and targets get the plain function.

#include <omp.h>

#include <utility>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define LAMINA_VECTOR_CLONES                                                                       \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define LAMINA_VECTOR_CLONES
#endif

namespace lamina::core {

/// @return [begin, end) of the calling thread's static share of [0, n)
/// (the whole range outside a parallel region). Contiguous shares keep each
/// thread on the same part of the vectors in every loop of a solve.
inline std::pair<int, int> threadRange(int n) {
  const long t = omp_get_thread_num(), nt = omp_get_num_threads();
  return {static_cast<int>(n * t / nt), static_cast<int>(n * (t + 1) / nt)};
}

} // namespace lamina::core
