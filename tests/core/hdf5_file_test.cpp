// The RAII HDF5 wrapper: double and int datasets and string/double attributes
// come back exactly as written (HDF5 stores native binary), groups are made
// on the way, and failures name the file and the object.

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <unistd.h>

namespace core = lamina::core;
namespace fs = std::filesystem;

TEST(Hdf5File, DatasetsAndAttributesRoundTripExactly) {
  const lamina::test::TempDir d;
  const fs::path p = d.path() / "fields.h5";
  const std::vector<double> values{
      1.0 / 3.0, -0.0, 1e308, std::numeric_limits<double>::denorm_min(), std::nan(""), 150e9};
  const std::vector<std::int32_t> phases{0, 1, -7, 2147483647, -2147483647 - 1, 3, 4, 5};
  {
    core::H5File f(p, core::H5File::Mode::Create);
    f.createGroup("/cell/phase");
    f.writeDoubles("/cell/values", values.data(), {2, 3});
    f.writeInts("/cell/phase/map", phases.data(), {2, 2, 2});
    f.writeDoubles("/deep/auto/made", values.data(), {6}); // intermediate groups created
    f.writeAttribute("/", "format", "lamina-phase-map");
    f.writeAttribute("/cell/values", "unit", "Pa");
    f.writeAttribute("/cell", "volume_fraction", 0.19);
    f.writeAttribute("/", "format", "lamina-phase-map v2"); // replacing an attribute
    f.flush();
  }
  const core::H5File f(p, core::H5File::Mode::ReadOnly);
  std::vector<std::uint64_t> dims;
  const auto v = f.readDoubles("/cell/values", dims);
  EXPECT_EQ(dims, (std::vector<std::uint64_t>{2, 3}));
  ASSERT_EQ(v.size(), values.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (std::isnan(values[i]))
      EXPECT_TRUE(std::isnan(v[i]));
    else
      EXPECT_EQ(v[i], values[i]) << i;
  }
  EXPECT_TRUE(std::signbit(v[1])); // -0.0 kept
  const auto m = f.readInts("/cell/phase/map", dims);
  EXPECT_EQ(dims, (std::vector<std::uint64_t>{2, 2, 2}));
  EXPECT_EQ(m, phases);
  EXPECT_TRUE(f.exists("/deep/auto/made"));
  EXPECT_TRUE(f.exists("/cell/phase"));
  EXPECT_FALSE(f.exists("/cell/nothing"));
  EXPECT_FALSE(f.exists("/no/such/path"));
  EXPECT_EQ(f.readStringAttribute("/", "format"), "lamina-phase-map v2");
  EXPECT_EQ(f.readStringAttribute("/cell/values", "unit"), "Pa");
  // The wrapper has no double-attribute reader: read it with the C API.
  const hid_t file = H5Fopen(p.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t a = H5Aopen_by_name(file, "/cell", "volume_fraction", H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(a, 0);
  double vf = 0;
  EXPECT_GE(H5Aread(a, H5T_NATIVE_DOUBLE, &vf), 0);
  EXPECT_EQ(vf, 0.19);
  H5Aclose(a);
  H5Fclose(file);
}

TEST(Hdf5File, RewritingADatasetReplacesIt) {
  const lamina::test::TempDir d;
  const fs::path p = d.path() / "x.h5";
  core::H5File f(p, core::H5File::Mode::Create);
  const std::vector<double> a{1, 2, 3}, b{4, 5};
  f.writeDoubles("/v", a.data(), {3});
  f.writeDoubles("/v", b.data(), {2});
  std::vector<std::uint64_t> dims;
  EXPECT_EQ(f.readDoubles("/v", dims), b);
}

TEST(Hdf5File, FailuresNameFileAndObject) {
  const lamina::test::TempDir d;
  const fs::path p = d.path() / "x.h5";
  try {
    core::H5File f(d.path() / "missing.h5", core::H5File::Mode::ReadOnly);
    FAIL() << "no error";
  } catch (const lamina::Error& e) {
    EXPECT_EQ(e.context().file, (d.path() / "missing.h5").string());
  }
  core::H5File f(p, core::H5File::Mode::Create);
  std::vector<std::uint64_t> dims;
  try {
    f.readDoubles("/nothing", dims);
    FAIL() << "no error";
  } catch (const lamina::Error& e) {
    EXPECT_EQ(e.context().file, p.string());
    EXPECT_EQ(e.context().key, "/nothing");
  }
  try {
    f.readStringAttribute("/", "absent");
    FAIL() << "no error";
  } catch (const lamina::Error& e) {
    EXPECT_NE(std::string(e.what()).find("absent"), std::string::npos) << e.what();
  }
}
