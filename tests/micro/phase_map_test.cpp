// micro::PhaseMap: an owned map behaves as the std::vector it was before;
// a borrowed map reads the memory it was given without copying it, keeps
// that memory alive for as long as a map borrows it, and is copied into
// storage of its own before anything writes to it.
#include "micro/phase_map.hpp"
#include "micro/voxel_cell.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace {

using lamina::micro::PhaseMap;

TEST(PhaseMap, OwnedIsTheVector) {
  PhaseMap m = std::vector<std::int32_t>{0, 1, 1, 0};
  EXPECT_FALSE(m.borrowed());
  EXPECT_EQ(m.size(), 4u);
  EXPECT_EQ(m[1], 1);
  EXPECT_EQ(m, (std::vector<std::int32_t>{0, 1, 1, 0}));
  m.values()[0] = 2;
  EXPECT_EQ(m[0], 2);
  m.resize(6);
  EXPECT_EQ(m, (std::vector<std::int32_t>{2, 1, 1, 0, 0, 0}));
  PhaseMap copy = m;
  copy.assign(2, 5);
  EXPECT_EQ(m.size(), 6u); // a copy of an owned map is its own
  EXPECT_EQ(copy, (std::vector<std::int32_t>{5, 5}));
}

TEST(PhaseMap, BorrowedReadsInPlaceAndKeepsTheMemory) {
  auto memory = std::make_shared<std::vector<std::int32_t>>(std::vector<std::int32_t>{1, 0, 1});
  std::weak_ptr<std::vector<std::int32_t>> watch = memory;
  const std::int32_t* data = memory->data();
  PhaseMap m = PhaseMap::borrow(data, memory->size(), memory);
  memory.reset(); // the map keeps it alive
  EXPECT_TRUE(m.borrowed());
  EXPECT_EQ(m.data(), data);
  EXPECT_FALSE(watch.expired());
  {
    const PhaseMap copy = m; // borrows the same memory
    EXPECT_EQ(copy.data(), data);
    m = PhaseMap();
    EXPECT_FALSE(watch.expired());
    EXPECT_EQ(copy, (std::vector<std::int32_t>{1, 0, 1}));
  }
  EXPECT_TRUE(watch.expired()); // the last borrow went
}

TEST(PhaseMap, WritingABorrowedMapCopiesItFirst) {
  std::vector<std::int32_t> memory{1, 0, 1};
  PhaseMap m = PhaseMap::borrow(memory.data(), memory.size(), nullptr);
  EXPECT_TRUE(m.borrowed());
  m.values()[0] = 0;
  EXPECT_FALSE(m.borrowed());
  EXPECT_EQ(memory[0], 1); // never written
  EXPECT_EQ(m, (std::vector<std::int32_t>{0, 0, 1}));
}

TEST(PhaseMap, AUnitCellCountsABorrowedMap) {
  std::vector<std::int32_t> memory{0, 1, 1, 1, 0, 1, 1, 1};
  lamina::micro::UnitCell cell;
  cell.n = {2, 2, 2};
  cell.phase_count = 2;
  cell.phase = PhaseMap::borrow(memory.data(), memory.size(), nullptr);
  cell.countFractions();
  EXPECT_EQ(cell.voxel_fraction, (std::vector<double>{0.25, 0.75}));
  EXPECT_EQ(cell.voxels(), 8u);
}

} // namespace
