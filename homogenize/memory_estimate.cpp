#include "homogenize/memory_estimate.hpp"

namespace lamina::homogenize {

bool singleVectors(const Options& opt) {
  return floatVectors(opt.precision.value_or(autoPrecision(opt.tol)), opt.tol);
}

double linearSolveBytes(std::uint64_t voxels, const Options& opt, bool has_size, int ranks,
                        int rank) {
  // per voxel three CG vectors (72 bytes in double, 36 in single precision),
  // the FFT buffer, the phase index and with the energy estimate six
  // displacement fields (a seventh in double for the dispersion sink when
  // single), over the ranks; rank 0 also holds the whole phase map while it
  // scatters it
  const bool single = singleVectors(opt);
  const std::uint64_t field = single ? 12 : 24; // one displacement-like field
  const std::uint64_t per_voxel = 4 + 4 * field +
                                  (opt.estimate == Estimate::Energy ? 6 * field : 0) +
                                  (has_size && single ? 24 : 0);
  // a cell with a size also gets its dispersion tensor, formed on rank 0
  // from the whole grid: the spectra h_hat of the six cases (6 x 3 complex
  // doubles per mode of the half spectrum, 146 bytes per voxel), the FFT
  // buffer and the density spectrum (32), the gathered displacement of a
  // case when distributed (24)
  const std::uint64_t dispersion_per_voxel = has_size ? 180 + (ranks > 1 ? 24 : 0) : 0;
  return double(voxels * per_voxel / static_cast<std::uint64_t>(ranks) +
                (rank == 0 ? (8 + dispersion_per_voxel) * voxels : 0));
}

} // namespace lamina::homogenize
