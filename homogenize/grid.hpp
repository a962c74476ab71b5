#pragma once
/// @file grid.hpp
/// @brief The periodic voxel grid of a cell problem and 64-byte aligned
/// fields on it (FFTW's new-array execute needs equal alignment).

#include <array>
#include <cstddef>
#include <memory>

namespace lamina::homogenize {

/// A periodic grid of n0 x n1 x n2 voxels (and as many nodes, at the voxel
/// corners), C order, x slowest: index (i*n1 + j)*n2 + k.
struct Grid {
  std::array<int, 3> n{0, 0, 0};          ///< voxels along x, y, z
  std::array<double, 3> h{1.0, 1.0, 1.0}; ///< voxel edge lengths
  /// @return the number of voxels (= nodes)
  std::size_t size() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
           static_cast<std::size_t>(n[2]);
  }
  /// @return complex entries of one r2c transform: n0 * n1 * (n2/2 + 1)
  std::size_t complexSize() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) *
           static_cast<std::size_t>(n[2] / 2 + 1);
  }
};

/// Owning array of T (double or float), 64-byte aligned (2 MiB and offered
/// to huge pages from 2 MiB up; fft.cpp), no copies.
template <class T>
class AlignedArray {
public:
  AlignedArray() = default;
  /// Allocates @p count values (uninitialized); throws std::bad_alloc on failure.
  explicit AlignedArray(std::size_t count);
  /// @return the data pointer
  T* data() { return data_.get(); }
  /// @return the data pointer
  const T* data() const { return data_.get(); }
  /// @return the number of values
  std::size_t size() const { return size_; }

private:
  struct Free {
    void operator()(T* p) const;
  };
  std::unique_ptr<T, Free> data_;
  std::size_t size_ = 0;
};

/// Owning array of doubles (see AlignedArray).
using AlignedBuffer = AlignedArray<double>;

/// A displacement-like field: 3 components of grid.size() doubles each,
/// stored one component after the other (the layout the batched FFT takes).
using VectorField = AlignedBuffer;

} // namespace lamina::homogenize
