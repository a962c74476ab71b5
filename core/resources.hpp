#pragma once
/// @file resources.hpp
/// @brief What the machine offers a run (memory, hardware threads), so work
/// that cannot fit is refused up front with the amount it needs instead of
/// failing inside an allocation or a thread pool.

#include "core/error.hpp"

#include <cstdint>
#include <string>

namespace lamina::core {

/// @return bytes this process may still allocate: MemAvailable of
/// /proc/meminfo, lowered to the cgroup memory limit and RLIMIT_AS when those
/// are set; 0 when nothing is known (then no estimate is refused).
double availableMemoryBytes();

/// @return the largest resident set this process has had so far, in bytes
/// (getrusage's ru_maxrss); 0 when the system does not tell
double peakResidentBytes();

/// @return the hardware threads this process may run on (its CPU affinity
/// mask; at least 1)
int hardwareThreads();

/// @return @p bytes as "1.5 GiB", "320 MiB", "12 KiB" or "100 B"
std::string formatBytes(double bytes);

/// Throws lamina::Error with @p context when @p bytes (an estimate of what
/// @p what needs) exceeds availableMemoryBytes(): "WHAT needs about N of
/// memory, M available", followed by "; " and @p advice when one is given
/// (what the user can do instead). Also refuses a non-finite estimate.
void requireMemory(double bytes, const std::string& what, const ErrorContext& context = {},
                   const std::string& advice = {});

/// Throws lamina::Error naming @p option when @p threads is negative or above
/// hardwareThreads() (0 = all of them; more threads than cores only slow the
/// compute-bound kernels, and OpenMP fails outright at tens of thousands).
void checkThreads(int threads, const std::string& option);

} // namespace lamina::core
