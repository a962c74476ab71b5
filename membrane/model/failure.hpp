#pragma once
/// @file failure.hpp
/// @brief Failure-onset record of the large-deflection model: per element the
/// first time a threshold of its section (maximum principal Green-Lagrange
/// strain, maximum principal Cauchy stress) was crossed, and the first
/// element of all (membrane paper, conclusion: where and when fabric fails).

#include "core/enum_names.hpp"

#include <string>
#include <vector>

namespace lamina::membrane {

/// Which threshold an element crossed.
enum class FailureCriterion : int {
  None = 0,   ///< not failed
  Strain = 1, ///< maximum principal strain
  Stress = 2, ///< maximum principal stress
};

/// The criterion names of the outputs (summary.json, fields).
inline constexpr auto kFailureCriterionNames = core::enumNames<FailureCriterion>(
    {{"none", FailureCriterion::None},
     {"strain", FailureCriterion::Strain},
     {"stress", FailureCriterion::Stress}});

/// @return "strain", "stress" or "none"
inline std::string failureName(FailureCriterion c) {
  return std::string(kFailureCriterionNames.name(c));
}

/// Per-element failure times and the onset.
struct FailureRecord {
  std::vector<double> time;                ///< first crossing per element (s; -1: none)
  std::vector<FailureCriterion> criterion; ///< which threshold, per element
  int first_element = -1;                  ///< the element that failed first (-1: none)
  double first_time = -1;                  ///< its time (s)
  FailureCriterion first_criterion = FailureCriterion::None; ///< and criterion
  /// Records a crossing of element @p e at time @p t (kept only if it is the first).
  void mark(int e, double t, FailureCriterion c) {
    if (time[e] >= 0)
      return;
    time[e] = t;
    criterion[e] = c;
    if (first_element < 0 || t < first_time || (t == first_time && e < first_element)) {
      first_element = e;
      first_time = t;
      first_criterion = c;
    }
  }
};

} // namespace lamina::membrane
