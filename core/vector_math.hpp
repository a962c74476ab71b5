#pragma once
/// @file vector_math.hpp
/// @brief exp and log in loops over lanes (core/vector_clones.hpp), by
/// glibc's vector math library.
///
/// glibc's libmvec (linked through libm) has exp and log for each vector
/// width (2, 4 and 8 lanes; at most 4 ulp from the correctly rounded value,
/// against the scalar functions' 1). Declared here as SIMD variants of exp
/// and log, a LAMINA_LANES loop of std::exp or std::log calls vectorizes
/// into calls of the variant of the clone's width, in a file compiled with
/// -fno-math-errno (a function that may set errno cannot be vectorized).
/// Include this header only in such files: elsewhere an OpenMP SIMD loop
/// would change from the scalar functions to these. Other compilers and
/// libraries: the scalar functions.

#include "core/vector_clones.hpp"

#include <cmath>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__)
extern "C" double exp(double) noexcept __attribute__((simd("notinbranch")));
extern "C" double log(double) noexcept __attribute__((simd("notinbranch")));
#endif
