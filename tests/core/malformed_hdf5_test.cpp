/// @file malformed_hdf5_test.cpp
/// @brief HDF5 datasets whose header lies about their content (a corrupted
/// shape or value size, as the checkpoint fuzzer produced): read, they made
/// H5File allocate without bound (std::length_error, or gigabytes inside
/// H5Dread). Each is refused, naming the file and the dataset, before any
/// allocation.

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "test_util.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace core = lamina::core;
using lamina::test::errorOf;
using lamina::test::TempDir;

namespace {
/// Writes /x, 7 x 9 doubles, to @p path; @return the file's bytes.
std::string writeSeven(const std::filesystem::path& path) {
  {
    core::H5File f(path, core::H5File::Mode::Create);
    const std::vector<double> v(63, 1.5);
    f.writeDoubles("/x", v.data(), {7, 9});
  }
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Replaces, in @p bytes, the dataspace dims (7, 9) by (7, @p second).
void patchDims(std::string& bytes, std::uint64_t second) {
  std::string dims(16, '\0');
  dims[0] = 7;
  dims[8] = 9;
  const auto at = bytes.find(dims);
  ASSERT_NE(at, std::string::npos) << "no dataspace (7, 9) in the file";
  std::memcpy(&bytes[at + 8], &second, sizeof second); // little endian, as HDF5 stores it
}

std::string readError(const std::filesystem::path& path) {
  return errorOf([&] {
    const core::H5File f(path, core::H5File::Mode::ReadOnly);
    std::vector<std::uint64_t> dims;
    f.readDoubles("/x", dims);
  });
}
} // namespace

TEST(MalformedHdf5, ShapeBeyondTheStoredBytesIsRefused) {
  const TempDir dir;
  const auto path = dir / "shape.h5";
  // 7 x 900 doubles need 50400 bytes, the file holds 504 for /x; 7 x 2^61
  // overflows any allocation.
  const std::vector<std::pair<std::uint64_t, std::string>> lies{
      {900, "fewer bytes than its shape needs"}, {std::uint64_t(1) << 61, "too large"}};
  for (const auto& [second, why] : lies) {
    std::string bytes = writeSeven(path);
    ASSERT_EQ(readError(path), "");
    patchDims(bytes, second);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    const std::string e = readError(path);
    EXPECT_NE(e.find(path.string()), std::string::npos) << e;
    EXPECT_NE(e.find("/x"), std::string::npos) << e;
    EXPECT_NE(e.find(why), std::string::npos) << e;
  }
}
