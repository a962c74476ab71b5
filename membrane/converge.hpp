#pragma once
/// @file converge.hpp
/// @brief The convergence study of the membrane paper, section 4.
///
/// Level 0 is the case as given (a structured rectangle, nx x ny squares,
/// time step tau). Level k splits every square into 4^k (nx, ny times 2^k)
/// and divides tau by 2^k. Every level is sampled at the nodes of level 0
/// and at the times of level 0's steps (every `sample_every` of them). The
/// norms of the differences between consecutive levels (L1 and L2 as means
/// over samples, Linf as the maximum) give the observed rate as the negated
/// least-squares slope of log2(difference) against k (Table 3).

#include "membrane/io/case_file.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace lamina::membrane {

/// Result of a convergence study.
struct ConvergenceStudy {
  std::vector<int> nx;                   ///< squares along x per level
  std::vector<double> dt;                ///< time step per level
  std::vector<std::array<double, 3>> du; ///< displacement differences (L1, L2, Linf), levels 1..K-1
  std::vector<std::array<double, 3>> dv; ///< velocity differences
  std::array<double, 3> rate_u{};        ///< observed displacement rates (L1, L2, Linf)
  std::array<double, 3> rate_v{};        ///< observed velocity rates
  double wall_s = 0;                     ///< total time (s)
  /// @return the study as JSON
  nlohmann::json toJson() const;
  /// @return the study as a text table like the paper's Table 3: a legend,
  /// a header, one row per level (nx, dt, its differences to the level
  /// before) and the rates last, in fixed-width left-aligned columns (4
  /// significant digits)
  std::string toTable() const;
};

/// Runs @p levels (>= 3) levels of the case in @p path.
ConvergenceStudy runConvergence(const std::filesystem::path& path,
                                const std::vector<std::string>& overrides,
                                const MaterialSources& sources, int levels, int sample_every = 1,
                                bool quiet = true);

/// @return minus the least-squares slope of log2(e_k) against k
double observedRate(const std::vector<double>& e);

} // namespace lamina::membrane
