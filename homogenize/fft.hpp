#pragma once
/// @file fft.hpp
/// @brief Batched real-to-complex / complex-to-real 3-D FFTs of the three
/// components of a vector field, planned once and reused (FFTW, threads).

#include "homogenize/grid.hpp"

#include <fftw3.h>

#include <string>

namespace lamina::homogenize {

/// FFTW plans for 3 components at once (fftw_plan_many_dft_r2c/c2r).
/// Contract: forward() keeps its real input; backward() destroys its complex
/// input; both take any arrays allocated like AlignedBuffer. Unnormalized
/// (backward(forward(x)) = N x).
class VectorFft {
public:
  /// Plans for @p grid with @p threads FFTW threads (0: leave FFTW's default).
  /// @param measure FFTW_MEASURE (planning takes seconds at 128^3, transforms
  /// then run about twice as fast as with FFTW_ESTIMATE). Measured plans are
  /// kept as FFTW wisdom in wisdomPath() and reused by later runs.
  VectorFft(const Grid& grid, int threads, bool measure);

  /// The wisdom file: $LAMINA_FFTW_WISDOM, else $XDG_CACHE_HOME/lamina/fftw-wisdom,
  /// else ~/.cache/lamina/fftw-wisdom (empty path: none).
  static std::string wisdomPath();
  ~VectorFft();
  VectorFft(const VectorFft&) = delete;
  VectorFft& operator=(const VectorFft&) = delete;

  /// real (3 x N) -> complex (3 x complexSize)
  void forward(const double* in, fftw_complex* out) const;
  /// complex (3 x complexSize) -> real (3 x N); destroys @p in
  void backward(fftw_complex* in, double* out) const;
  /// @return the complex work array (3 x complexSize), owned by this object
  fftw_complex* work() const { return work_; }

private:
  Grid grid_;
  fftw_complex* work_ = nullptr;
  fftw_plan r2c_ = nullptr, c2r_ = nullptr;
};

} // namespace lamina::homogenize
