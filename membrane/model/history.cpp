#include "membrane/model/history.hpp"

#include "core/error.hpp"
#include "core/format.hpp"

#include <cmath>

namespace lamina::membrane {

const Eigen::VectorXd& historyEntry(const History& h, const std::string& key, Eigen::Index size) {
  const auto it = h.find(key);
  if (it == h.end())
    throw Error("checkpoint has no entry '" + key + "'");
  if (size >= 0 && it->second.size() != size)
    throw Error("checkpoint entry '" + key + "' has " + std::to_string(it->second.size()) +
                " values, this run needs " + std::to_string(size));
  return it->second;
}

long historyInteger(const History& h, const std::string& key, Eigen::Index size, Eigen::Index i,
                    long lo, long hi) {
  const double x = historyEntry(h, key, size)[i];
  if (!(x >= static_cast<double>(lo) && x <= static_cast<double>(hi)) || x != std::floor(x))
    throw Error("checkpoint entry '" + key + "' value " + std::to_string(i) + " is " +
                core::formatShort(x) + ", not an integer in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "]");
  return static_cast<long>(x);
}

} // namespace lamina::membrane
