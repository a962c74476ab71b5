#include "core/memory.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace lamina::core {

std::uint64_t availableMemory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:")
      return kib * 1024;
  return 0;
}

std::string formatBytes(std::uint64_t bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024 && u < 4) {
    v /= 1024;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", v, units[u]);
  return buf;
}

void requireMemory(std::uint64_t bytes, const std::string& what, const ErrorContext& context,
                   const std::string& advice) {
  const std::uint64_t avail = availableMemory();
  if (avail == 0 || bytes <= avail)
    return;
  std::ostringstream os;
  os << what << " needs " << formatBytes(bytes) << " but only " << formatBytes(avail)
     << " is available";
  if (!advice.empty())
    os << "; " << advice;
  throw Error(os.str(), context);
}

} // namespace lamina::core
