#include "micro/voxel_cell.hpp"

namespace lamina::micro {

void UnitCell::countFractions() {
  // whole voxels counted as integers, cut voxels' shares summed apart (no
  // fraction is subtracted from a large count: the sum stays 1 to round-off)
  std::vector<std::size_t> counts(static_cast<std::size_t>(phase_count), 0);
  std::vector<double> shares(counts.size(), 0.0);
  for (std::int32_t p : phase)
    ++counts[static_cast<std::size_t>(p)];
  for (const CompositeVoxel& c : composites) {
    --counts[static_cast<std::size_t>(phase[c.index])];
    shares[static_cast<std::size_t>(c.inside)] += c.fraction;
    shares[static_cast<std::size_t>(c.outside)] += 1 - c.fraction;
  }
  voxel_fraction.assign(counts.size(), 0.0);
  for (std::size_t i = 0; i < counts.size(); ++i)
    voxel_fraction[i] =
        (static_cast<double>(counts[i]) + shares[i]) / static_cast<double>(phase.size());
}

} // namespace lamina::micro
