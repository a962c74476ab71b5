#include "core/resources.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sched.h>
#include <sstream>
#include <sys/resource.h>

namespace lamina::core {

namespace {

/// @return the number in the first line of @p path, or NaN ("max", absent).
double numberIn(const char* path) {
  std::ifstream in(path);
  double v = std::nan("");
  if (!(in >> v))
    return std::nan("");
  return v;
}

} // namespace

double availableMemoryBytes() {
  double avail = std::nan("");
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    double kb = 0;
    if (std::sscanf(line.c_str(), "MemAvailable: %lf kB", &kb) == 1) {
      avail = kb * 1024.0;
      break;
    }
  }
  // A container's limit (cgroup v2, then v1) minus what it uses already.
  const double limit2 = numberIn("/sys/fs/cgroup/memory.max");
  const double used2 = numberIn("/sys/fs/cgroup/memory.current");
  if (std::isfinite(limit2) && std::isfinite(used2))
    avail = std::isfinite(avail) ? std::min(avail, limit2 - used2) : limit2 - used2;
  const double limit1 = numberIn("/sys/fs/cgroup/memory/memory.limit_in_bytes");
  const double used1 = numberIn("/sys/fs/cgroup/memory/memory.usage_in_bytes");
  if (std::isfinite(limit1) && std::isfinite(used1) && limit1 < 1e18)
    avail = std::isfinite(avail) ? std::min(avail, limit1 - used1) : limit1 - used1;
  rlimit as{};
  if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
    avail = std::isfinite(avail) ? std::min(avail, static_cast<double>(as.rlim_cur))
                                 : static_cast<double>(as.rlim_cur);
  return std::isfinite(avail) ? std::max(avail, 0.0) : 0.0;
}

double peakResidentBytes() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0)
    return 0;
  return static_cast<double>(usage.ru_maxrss) * 1024.0; // Linux: KiB
}

int hardwareThreads() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0)
    return std::max(1, CPU_COUNT(&set));
  return 1;
}

std::string formatBytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  std::ostringstream os;
  os.precision(bytes < 10 && u > 0 ? 2 : 3);
  os << bytes << " " << units[u];
  return os.str();
}

void requireMemory(double bytes, const std::string& what, const ErrorContext& context,
                   const std::string& advice) {
  const std::string tail = advice.empty() ? std::string() : "; " + advice;
  if (!std::isfinite(bytes))
    throw Error(what + " needs more memory than can be counted" + tail, context);
  const double avail = availableMemoryBytes();
  if (avail > 0 && bytes > avail)
    throw Error(what + " needs about " + formatBytes(bytes) + " of memory, " + formatBytes(avail) +
                    " available" + tail,
                context);
}

void checkThreads(int threads, const std::string& option) {
  const int hw = hardwareThreads();
  if (threads < 0 || threads > hw)
    throw Error("must be in [0, " + std::to_string(hw) + "] (0 = all " + std::to_string(hw) +
                    " hardware threads of this machine), got " + std::to_string(threads),
                {"", 0, option});
}

} // namespace lamina::core
