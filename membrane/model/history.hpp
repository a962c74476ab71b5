#pragma once
/// @file history.hpp
/// @brief Named arrays of doubles: what a model, a time scheme or a run
/// saves in a checkpoint besides the State, and the checked readers of a
/// restored one (a checkpoint is input).

#include <Eigen/Dense>

#include <map>
#include <string>

namespace lamina::membrane {

/// Named arrays of doubles. Keys are '/'-separated paths ("forces/external").
using History = std::map<std::string, Eigen::VectorXd>;

/// @return entry @p key of @p h, which must exist and (when @p size >= 0)
/// have @p size values; throws lamina::Error naming the key otherwise
const Eigen::VectorXd& historyEntry(const History& h, const std::string& key,
                                    Eigen::Index size = -1);
/// @return value @p i of entry @p key of @p h (which must hold @p size
/// values) as an integer, which must be one (no fraction) in [@p lo, @p hi];
/// throws lamina::Error naming the key and the range otherwise
long historyInteger(const History& h, const std::string& key, Eigen::Index size, Eigen::Index i,
                    long lo, long hi);

} // namespace lamina::membrane
