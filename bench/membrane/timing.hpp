#pragma once
/// @file timing.hpp
/// @brief The clocks and the timing loop of the membrane benchmarks
/// (bench/membrane/*.cpp).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <vector>

namespace lamina::bench {

/// @return the CPU time of the process, all threads (s)
inline double cpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// @return a monotonic wall clock (s)
inline double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Best and median wall and mean CPU time of one call (s).
struct Timing {
  double best = 0, cpu = 0, median = 0;
};

/// Runs @p fn @p reps times; prints best and median wall, mean CPU (ms).
template <class F>
inline Timing timeIt(const char* what, int reps, F&& fn) {
  fn(); // warm caches and first-touch pages
  std::vector<double> wall;
  const double c0 = cpuSeconds();
  for (int r = 0; r < reps; ++r) {
    const double a = wallSeconds();
    fn();
    wall.push_back(wallSeconds() - a);
  }
  const double cpu = (cpuSeconds() - c0) / reps;
  std::sort(wall.begin(), wall.end());
  std::printf("%-34s best %8.3f ms  median %8.3f ms  cpu %8.3f ms\n", what, 1e3 * wall.front(),
              1e3 * wall[wall.size() / 2], 1e3 * cpu);
  return {wall.front(), cpu, wall[wall.size() / 2]};
}

} // namespace lamina::bench
