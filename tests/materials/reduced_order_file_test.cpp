/// @file reduced_order_file_test.cpp
/// @brief The side file of a reduced-order cell (materials/reduced_order.hpp):
/// arrays round-trip bit for bit, a malformed file is refused naming the file
/// and the dataset, and the checksum sees a change of one byte.

#include "core/hdf5_file.hpp"
#include "laminate_reduced_order.hpp"
#include "materials/reduced_order.hpp"
#include "reduced_order_cells.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>

namespace lamina {
namespace {

/// A two-layer laminate model with exact A and P (the oracle) and a made-up
/// positive R and Q: enough for the file mechanics.
materials::ReducedOrderModel laminateModel() {
  materials::ReducedOrderModel m;
  materials::ReducedOrderPhase soft, hard;
  soft.name = "soft";
  soft.law.kind = materials::LawKind::Isotropic;
  soft.law.C = materials::Stiffness::fromLame(2e9, 1e9);
  soft.density = 1000;
  hard.name = "hard";
  hard.law.kind = materials::LawKind::Isotropic;
  hard.law.C = materials::Stiffness::fromLame(20e9, 10e9);
  hard.density = 3000;
  m.phases = {soft, hard};
  m.partition_phase = {0, 1};
  m.fraction = {0.75, 0.25};
  test::laminateReducedOrder({soft.law.C.matrix(), hard.law.C.matrix()}, m.fraction, m.A, m.P);
  Eigen::MatrixXd B = Eigen::MatrixXd::Random(12, 12);
  m.R = B * B.transpose() * 1e-12;
  m.Q = Eigen::MatrixXd::Random(6, 12) * 1e-12;
  m.D_lin = materials::Matrix6::Identity() * 1e-13;
  m.C = m.fraction[0] * soft.law.C.matrix() * m.A[0] + m.fraction[1] * hard.law.C.matrix() * m.A[1];
  m.density = 1500;
  return m;
}

TEST(ReducedOrderFile, ArraysRoundTripBitForBit) {
  test::TempDir dir;
  const materials::ReducedOrderModel m = laminateModel();
  const auto path = dir.path() / "cell.h5";
  materials::writeReducedOrderArrays(path, m);
  materials::ReducedOrderModel r;
  r.phases = m.phases;
  materials::readReducedOrderArrays(path, r);
  EXPECT_EQ(r.partition_phase, m.partition_phase);
  EXPECT_EQ(r.fraction, m.fraction);
  for (std::size_t a = 0; a < 2; ++a)
    EXPECT_EQ(r.A[a], m.A[a]);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_EQ(r.P[k], m.P[k]);
  EXPECT_EQ(r.R, m.R);
  EXPECT_EQ(r.Q, m.Q);
  EXPECT_EQ(r.D_lin, m.D_lin);
  EXPECT_EQ(r.C, m.C);
  EXPECT_EQ(r.density, m.density);
}

// A clustering cell adds its interaction tensors and scheme (format 2).
TEST(ReducedOrderFile, ClusteringArraysRoundTripBitForBit) {
  test::TempDir dir;
  const materials::ReducedOrderModel m = test::clustering(laminateModel());
  const auto path = dir.path() / "cell.h5";
  materials::writeReducedOrderArrays(path, m);
  materials::ReducedOrderModel r;
  r.phases = m.phases;
  materials::readReducedOrderArrays(path, r);
  EXPECT_EQ(r.scheme, materials::ReducedOrderScheme::Clustering);
  ASSERT_EQ(r.Ga.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(r.Ga[k], m.Ga[k]);
    EXPECT_EQ(r.Gb[k], m.Gb[k]);
  }
  EXPECT_EQ(r.P[1], m.P[1]);
  // without its interaction tensors the file is refused, naming the dataset
  {
    core::H5File f(path, core::H5File::Mode::ReadWrite);
    f.remove("/Gb");
  }
  const std::string msg = test::errorOf([&] {
    materials::ReducedOrderModel bad;
    bad.phases = m.phases;
    materials::readReducedOrderArrays(path, bad);
  });
  EXPECT_NE(msg.find("/Gb"), std::string::npos) << msg;
  // and a transformation model read back has none
  materials::writeReducedOrderArrays(path, laminateModel());
  materials::readReducedOrderArrays(path, r);
  EXPECT_EQ(r.scheme, materials::ReducedOrderScheme::Transformation);
  EXPECT_TRUE(r.Ga.empty());
}

// A clustering file whose attribute 'scheme' is not "clustering", or whose
// interaction tensors hold a NaN, is refused naming the file and what is wrong.
TEST(ReducedOrderFile, ClusteringFileWithAWrongSchemeOrANaNIsRefused) {
  test::TempDir dir;
  const materials::ReducedOrderModel m = test::clustering(laminateModel());
  const auto path = dir.path() / "cell.h5";
  const auto readBack = [&] {
    return test::errorOf([&] {
      materials::ReducedOrderModel r;
      r.phases = m.phases;
      materials::readReducedOrderArrays(path, r);
    });
  };
  for (const char* scheme : {"tfa", "sca", ""}) {
    materials::writeReducedOrderArrays(path, m);
    core::H5File(path, core::H5File::Mode::ReadWrite).writeAttribute("/", "scheme", scheme);
    const std::string msg = readBack();
    EXPECT_NE(msg.find("cell.h5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'scheme'"), std::string::npos) << msg;
  }
  materials::writeReducedOrderArrays(path, m);
  {
    core::H5File f(path, core::H5File::Mode::ReadWrite);
    std::vector<double> ga(4 * 36, 0.0);
    ga[7] = std::numeric_limits<double>::quiet_NaN();
    f.remove("/Ga");
    f.writeDoubles("/Ga", ga.data(), {2, 2, 6, 6});
  }
  const std::string msg = readBack();
  EXPECT_NE(msg.find("cell.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Ga or Gb"), std::string::npos) << msg;
}

TEST(ReducedOrderFile, ChecksumSeesOneChangedByte) {
  test::TempDir dir;
  const auto path = dir.path() / "cell.h5";
  materials::writeReducedOrderArrays(path, laminateModel());
  const std::string before = materials::fileChecksum(path);
  EXPECT_EQ(before.rfind("fnv1a64:", 0), 0u);
  EXPECT_EQ(before.size(), 8u + 16u);
  EXPECT_EQ(materials::fileChecksum(path), before); // deterministic
  std::string bytes = test::readFile(path);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 1);
  test::writeFile(path, bytes);
  EXPECT_NE(materials::fileChecksum(path), before);
}

TEST(ReducedOrderFile, WrongShapeIsRefusedNamingTheDataset) {
  test::TempDir dir;
  const auto path = dir.path() / "cell.h5";
  materials::writeReducedOrderArrays(path, laminateModel());
  {
    core::H5File f(path, core::H5File::Mode::ReadWrite);
    f.remove("/P");
    const std::vector<double> p(3 * 36, 0.0);
    f.writeDoubles("/P", p.data(), {3, 6, 6});
  }
  materials::ReducedOrderModel r;
  r.phases = laminateModel().phases;
  const std::string msg = test::errorOf([&] { materials::readReducedOrderArrays(path, r); });
  EXPECT_NE(msg.find("cell.h5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/P"), std::string::npos) << msg;
}

TEST(ReducedOrderFile, FractionsThatDoNotSumToOneAreRefused) {
  materials::ReducedOrderModel m = laminateModel();
  m.fraction[1] = 0.3;
  const std::string msg = test::errorOf([&] { m.validate("entry 'x'"); });
  EXPECT_NE(msg.find("sum"), std::string::npos) << msg;
  m = laminateModel();
  m.partition_phase[1] = 2;
  EXPECT_NE(test::errorOf([&] { m.validate("entry 'x'"); }).find("phase 2"), std::string::npos);
}

TEST(ReducedOrderFile, NotAReducedOrderFileIsRefused) {
  test::TempDir dir;
  const auto path = dir.path() / "other.h5";
  {
    core::H5File f(path, core::H5File::Mode::Create);
    const double x = 1;
    f.writeDoubles("/x", &x, {1});
  }
  materials::ReducedOrderModel r;
  const std::string msg = test::errorOf([&] { materials::readReducedOrderArrays(path, r); });
  EXPECT_NE(msg.find("not a reduced-order cell file"), std::string::npos) << msg;
}

} // namespace
} // namespace lamina
