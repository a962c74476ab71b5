#pragma once
/// @file phase_map.hpp
/// @brief The phase index per voxel of a unit cell (UnitCell::phase): an
/// int32 array that either owns its storage (a std::vector, what the cell
/// builders fill) or borrows memory someone else keeps alive (the Python
/// module's cells from a numpy label array, used without a copy).
///
/// Reading is the std::vector's API (size, operator[], data, begin/end,
/// comparison), on owned and borrowed maps alike. Writing goes through the
/// owned storage: assignment from a std::vector, resize, assign, and
/// values(), which first copies a borrowed map into storage of its own (a
/// borrowed map is never written to). Copying a borrowed map borrows the
/// same memory (and keeps it alive); copying an owned map copies it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace lamina::micro {

/// Phase index per voxel (C order, x slowest), owned or borrowed.
class PhaseMap {
public:
  using value_type = std::int32_t;            ///< the element type
  using size_type = std::size_t;              ///< sizes and indices
  using const_iterator = const std::int32_t*; ///< read-only iteration
  using iterator = const_iterator;            ///< iteration is read-only

  /// An empty, owned map.
  PhaseMap() = default;
  /// An owned map holding @p values (implicit: a builder's vector becomes the map).
  PhaseMap(std::vector<std::int32_t> values); // NOLINT(google-explicit-constructor)
  /// A map reading @p size values at @p data without a copy; @p keeper keeps
  /// that memory alive (released when the last map borrowing it goes; null:
  /// the caller keeps the memory alive for as long as a map reads it).
  static PhaseMap borrow(const std::int32_t* data, std::size_t size,
                         std::shared_ptr<const void> keeper);

  /// Owns @p values from now on (drops any borrow).
  PhaseMap& operator=(std::vector<std::int32_t> values);

  /// @return the number of voxels
  std::size_t size() const { return keeper_ ? borrowed_size_ : owned_.size(); }
  /// @return whether the map has no voxel
  bool empty() const { return size() == 0; }
  /// @return the phase index of voxel @p i (unchecked, as std::vector's)
  std::int32_t operator[](std::size_t i) const { return data()[i]; }
  /// @return the first value (size() of them follow)
  const std::int32_t* data() const { return keeper_ ? borrowed_ : owned_.data(); }
  /// @return the first value, for range loops
  const_iterator begin() const { return data(); }
  /// @return one past the last value
  const_iterator end() const { return data() + size(); }
  /// @return whether the map reads memory it does not own
  bool borrowed() const { return keeper_ != nullptr; }

  /// @return the owned storage, for writing; a borrowed map is first copied
  /// into storage of its own (and no longer borrows)
  std::vector<std::int32_t>& values();
  /// Owns @p n values, the first min(n, size()) kept, the others 0.
  void resize(std::size_t n);
  /// Owns @p n values equal to @p value.
  void assign(std::size_t n, std::int32_t value);
  /// @return a copy of the values as a std::vector
  std::vector<std::int32_t> toVector() const { return {begin(), end()}; }

  /// @return whether @p a and @p b hold the same values
  friend bool operator==(const PhaseMap& a, const PhaseMap& b);
  /// @return whether @p a and @p b differ
  friend bool operator!=(const PhaseMap& a, const PhaseMap& b) { return !(a == b); }
  /// @return whether @p a holds the values of @p b
  friend bool operator==(const PhaseMap& a, const std::vector<std::int32_t>& b);
  /// @return whether @p a and @p b differ
  friend bool operator!=(const PhaseMap& a, const std::vector<std::int32_t>& b) {
    return !(a == b);
  }

private:
  std::vector<std::int32_t> owned_;        ///< the values of an owned map
  std::shared_ptr<const void> keeper_;     ///< keeps borrowed memory alive (null: owned)
  const std::int32_t* borrowed_ = nullptr; ///< the borrowed memory (with keeper_)
  std::size_t borrowed_size_ = 0;          ///< values at borrowed_
};

} // namespace lamina::micro
