#pragma once
/// @file blast_pressure.hpp
/// @brief The air blast (or a user pressure history) as a pressure load on
/// the face that sees the charge: along each element's current normal on
/// its current area (the large-deflection model), or along e_z on the flat
/// reference membrane (the linear model); ElementPressure distributes it.
///
/// Per element e with centroid x and unit normal n (current, in node order;
/// or reference, e_z):
/// d = (charge - x) / |charge - x|, cos a = |n . d|, and the signed pressure
/// along n is p = -sign(n . d) P(t, cos a): it pushes the seen face away
/// from the charge. P combines the incident and the normally reflected
/// Friedlander pulses over the angle a (blast.hpp). The blast parameters
/// (arrival, peaks, duration, decays) are evaluated once per element at its
/// reference centroid: during the positive phase (milliseconds) the fabric
/// moves little. A pressure table acts along +n with p = table(t). Its work
/// is external work (energy.csv external_work).

#include "membrane/loads/blast.hpp"
#include "membrane/loads/element_pressure.hpp"

#include <optional>

namespace lamina::membrane {

/// Blast or tabulated pressure on a set of elements.
class BlastPressure final : public ElementPressure {
public:
  /// The blast of @p charge on @p elements of @p mesh in @p geometry. An
  /// Error names the first element whose scaled distance is outside the
  /// fits (Refuse policy).
  BlastPressure(std::string name, std::vector<int> elements, const Mesh& mesh,
                const BlastCharge& charge, Geometry geometry);
  /// The pressure history @p table on @p elements in @p geometry, along +n.
  BlastPressure(std::string name, std::vector<int> elements, PressureTable table,
                Geometry geometry);
  /// @return the earliest arrival (s; table: its first time)
  double firstArrival() const;
  /// @return the latest end of a positive phase (s; table: its last time)
  double lastEnd() const;
  /// @return the shortest positive phase of the loaded elements (s;
  /// table: its span from the first to the last row)
  double shortestPhase() const;

protected:
  double pressure(int e, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                  const LoadTime& when) const override;

private:
  std::optional<BlastCharge> charge_;
  std::vector<BlastHistory> histories_; ///< indexed by element (blast only)
  std::optional<PressureTable> table_;
};

} // namespace lamina::membrane
