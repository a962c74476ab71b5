#pragma once
/// @file vector_clones.hpp
/// @brief Kernels over lanes of points, vectorized for the CPU at hand: the
/// attribute that compiles a leaf kernel for several vector widths, the one
/// that keeps its helpers inside each width, the loop pragma and the flag
/// type of such kernels.
///
/// LAMINA_VECTOR_CLONES: the build targets baseline x86-64 (SSE2, no FMA),
/// which runs anywhere; a function carrying this attribute is compiled three
/// times (x86-64-v4 = AVX-512, x86-64-v3 = AVX2 + FMA, baseline) and the
/// loader picks the widest the CPU has (GCC function multi-versioning).
/// Put it only on leaf functions without OpenMP pragmas (GCC outlines the
/// body of a parallel region before cloning, so the clones would not reach
/// it). Other compilers and targets get the plain function.
///
/// LAMINA_CLONE_INLINE: a helper that such a kernel calls is compiled once,
/// for the baseline, unless it is inlined into each clone; this attribute
/// (always_inline) makes sure it is.
///
/// LAMINA_LANES before a loop over lanes that calls exp or log
/// (core/vector_math.hpp): vectorize it (OpenMP SIMD, in a file compiled
/// with -fopenmp-simd); without it GCC may unroll the loop into scalar calls.
///
/// A loop over lanes vectorizes when it has no inner loop, no
/// short-circuit && or || and no one-byte bools beside doubles: flags are
/// LaneMask, finiteness is finiteLane, and a file of such loops is compiled
/// with -fno-trapping-math (a ternary with a division is then a select).

#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define LAMINA_VECTOR_CLONES                                                                       \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define LAMINA_VECTOR_CLONES
#endif

#if defined(__GNUC__)
#define LAMINA_CLONE_INLINE inline __attribute__((always_inline))
#define LAMINA_LANES _Pragma("omp simd")
#else
#define LAMINA_CLONE_INLINE inline
#define LAMINA_LANES
#endif

namespace lamina::core {

/// A lane's flag, 0 or 1, as wide as a double.
using LaneMask = std::int64_t;

/// @return 1 where @p x is finite, else 0, in a form that vectorizes
/// (std::isfinite does not)
LAMINA_CLONE_INLINE LaneMask finiteLane(double x) {
  return std::abs(x) <= std::numeric_limits<double>::max();
}

} // namespace lamina::core
