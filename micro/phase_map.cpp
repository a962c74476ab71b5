#include "micro/phase_map.hpp"

#include <algorithm>
#include <utility>

namespace lamina::micro {

PhaseMap::PhaseMap(std::vector<std::int32_t> values) : owned_(std::move(values)) {}

PhaseMap PhaseMap::borrow(const std::int32_t* data, std::size_t size,
                          std::shared_ptr<const void> keeper) {
  PhaseMap m;
  m.keeper_ = keeper ? std::move(keeper) : std::make_shared<int>(0); // borrowed() is true
  m.borrowed_ = data;
  m.borrowed_size_ = size;
  return m;
}

PhaseMap& PhaseMap::operator=(std::vector<std::int32_t> values) {
  owned_ = std::move(values);
  keeper_.reset();
  return *this;
}

std::vector<std::int32_t>& PhaseMap::values() {
  if (keeper_) { // copy the borrowed values, then let the memory go
    owned_.assign(borrowed_, borrowed_ + borrowed_size_);
    keeper_.reset();
  }
  return owned_;
}

void PhaseMap::resize(std::size_t n) {
  values().resize(n);
}

void PhaseMap::assign(std::size_t n, std::int32_t value) {
  keeper_.reset();
  owned_.assign(n, value);
}

bool operator==(const PhaseMap& a, const PhaseMap& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

bool operator==(const PhaseMap& a, const std::vector<std::int32_t>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

} // namespace lamina::micro
