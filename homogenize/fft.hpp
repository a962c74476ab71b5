#pragma once
/// @file fft.hpp
/// @brief Real-to-complex / complex-to-real 3-D FFTs of the three components
/// of a vector field in double or single precision, planned once and reused
/// (FFTW, threads; FFTW's MPI slab decomposition when the grid is distributed).

#include "homogenize/distribution.hpp"
#include "homogenize/grid.hpp"

#include <memory>
#include <string>

namespace lamina::homogenize {

/// Floating-point precision of the transforms.
enum class Precision {
  Double, ///< 64-bit transforms
  Single  ///< 32-bit transforms (about 1.7x faster at 128^3, half the memory)
};

/// In-place FFTs of 3 components held in one spectrum buffer.
///
/// Layout: component c occupies chunkSize() complex entries from
/// spectrum<T>() + 2 c chunkSize(); in real space it is the padded array
/// nx x n1 x 2 (n2/2+1) of this process's x-slab, in Fourier space the
/// nx x n1 x (n2/2+1) complex modes of the same x-planes (FFTW's
/// non-transposed slab layout, also when serial). Unnormalized:
/// backward(forward(x)) = N x.
class VectorFft {
public:
  /// Plans for @p grid distributed by @p dist, with @p threads FFTW threads
  /// (0: leave FFTW's default).
  /// @param measure FFTW_MEASURE (planning takes seconds at 128^3, transforms
  /// then run about twice as fast as with FFTW_ESTIMATE). Measured plans are
  /// kept as FFTW wisdom in wisdomPath() and reused by later runs.
  VectorFft(const Grid& grid, const Distribution& dist, int threads, bool measure,
            Precision precision);
  ~VectorFft();
  VectorFft(const VectorFft&) = delete;
  VectorFft& operator=(const VectorFft&) = delete;

  /// The wisdom file: $LAMINA_FFTW_WISDOM, else $XDG_CACHE_HOME/lamina/fftw-wisdom,
  /// else ~/.cache/lamina/fftw-wisdom (empty path: none). Single precision
  /// and MPI plans use the same path with "-single" / "-mpi<ranks>" appended.
  static std::string wisdomPath();

  /// Loads @p r (3 components of the local slab, component-major, unpadded:
  /// dist.localSize() values each) and transforms it into the spectrum.
  /// V (the fields' type: double, or float for the linear solver's
  /// single-precision vectors) need not match precision().
  template <class V>
  void forward(const V* r);
  /// Transforms the spectrum back (destroying it) and stores it into @p z
  /// (same layout as forward's input).
  template <class V>
  void backward(V* z);
  /// The conjugate-gradient update r -= alpha w fused with forward(r): one
  /// pass over the fields.
  /// (With float fields the update runs in float.)
  template <class V>
  void forwardUpdate(V* r, double alpha, const V* w);
  /// backward() fused with the conjugate-gradient updates x += alpha p (when
  /// @p x is not null; the old p) and p = z + beta p (z is never stored):
  /// one pass that reads p once for both.
  template <class V>
  void backwardUpdate(V* p, double beta, V* x = nullptr, double alpha = 0);

  /// @return the precision
  Precision precision() const { return precision_; }
  /// @return complex entries per component in the spectrum buffer
  std::size_t chunkSize() const { return chunk_; }
  /// @return the spectrum as interleaved (re, im) values of type T (T must
  /// match precision())
  template <class T>
  T* spectrum() const;

  /// The plans of one precision (defined in fft.cpp).
  struct Plans;

private:
  template <class F>
  void eachRow(F&& f);
  Grid grid_;
  const Distribution& dist_;
  Precision precision_;
  std::size_t chunk_ = 0;
  void* buffer_ = nullptr;
  std::unique_ptr<Plans> plans_;
};

} // namespace lamina::homogenize
