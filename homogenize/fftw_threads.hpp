#pragma once
/// @file fftw_threads.hpp
/// @brief FFTW's thread support, initialised once per process for both
/// precisions: before any threaded plan (fft.hpp) and before fftw_mpi_init
/// (distribution.hpp; FFTW manual, section 6.11).

namespace lamina::homogenize {

/// Initialises FFTW's threads (double and single precision) once per process.
/// @return false when FFTW has no thread support
bool initFftwThreads();

} // namespace lamina::homogenize
