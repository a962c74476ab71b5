#pragma once
/// @file vector_clones.hpp
/// @brief The attribute that compiles a leaf kernel for several vector
/// widths, and the one that keeps its helpers inside each width.
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
/// Elementary functions in such a loop: glibc's vector math library
/// (libmvec, linked through libm) has exp and log for each vector width
/// (2, 4, 8 lanes; at most 4 ulp from the correctly rounded value, against
/// the scalar functions' 1). Declared here as SIMD variants of exp and log,
/// a loop of std::exp or std::log calls vectorizes into calls of the
/// variant of the clone's width, in a file compiled with -fno-math-errno
/// (a function that may set errno cannot be vectorized); elsewhere nothing
/// changes.

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define LAMINA_VECTOR_CLONES                                                                       \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define LAMINA_VECTOR_CLONES
#endif

#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__)
extern "C" double exp(double) noexcept __attribute__((simd("notinbranch")));
extern "C" double log(double) noexcept __attribute__((simd("notinbranch")));
#endif

/// LAMINA_LANES before a loop over lanes that calls exp or log: vectorize it
/// (OpenMP SIMD, in a file compiled with -fopenmp-simd); without it GCC may
/// unroll the loop into eight scalar calls first.
#if defined(_OPENMP) || defined(__GNUC__)
#define LAMINA_LANES _Pragma("omp simd")
#else
#define LAMINA_LANES
#endif

#if defined(__GNUC__)
#define LAMINA_CLONE_INLINE inline __attribute__((always_inline))
#else
#define LAMINA_CLONE_INLINE inline
#endif

namespace lamina::core {

/// A lane's flag, 0 or 1, as wide as a double: a loop over lanes that mixes
/// flags and doubles vectorizes (one-byte bools beside doubles do not).
using LaneMask = std::int64_t;

/// @return whether @p x is finite, in a form that vectorizes (std::isfinite
/// does not)
LAMINA_CLONE_INLINE bool finiteLane(double x) {
  return std::abs(x) <= std::numeric_limits<double>::max();
}

} // namespace lamina::core
