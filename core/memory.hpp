#pragma once
/// @file memory.hpp
/// @brief Memory needed against memory available, checked before a large
/// allocation so that a cell that cannot fit fails at once with a clear
/// message instead of being killed by the kernel half way through.

#include "core/error.hpp"

#include <cstdint>
#include <string>

namespace lamina::core {

/// @return the memory the kernel reports as available for a new allocation
/// (MemAvailable of /proc/meminfo, in bytes), or 0 if it cannot be read.
std::uint64_t availableMemory();

/// @return @p bytes as a short human string ("1.7 GiB", "230 MiB")
std::string formatBytes(std::uint64_t bytes);

/// Throws lamina::Error with @p context when @p bytes exceed the available
/// memory (unknown availability is not an error). The message says how much
/// @p what needs, how much is available and appends @p advice.
void requireMemory(std::uint64_t bytes, const std::string& what, const ErrorContext& context,
                   const std::string& advice);

} // namespace lamina::core
