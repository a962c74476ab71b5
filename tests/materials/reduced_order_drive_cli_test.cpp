/// @file reduced_order_drive_cli_test.cpp
/// @brief `materials drive` on a reduced-order library entry works as on
/// polyurea-gvbo (same CSV, the stress of the law built directly from the
/// cell, bit for bit through 17 digits), writes D_nonlin along the history
/// with --nonlinear-dispersion, and `materials show` / `list` / `export
/// --format json` describe the entry (partitions per phase, state doubles
/// per point of the documented layout).

#include "reduced_order_cells.hpp"

#include "materials/point_driver.hpp"
#include "materials/reduced_order_law.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace lamina {
namespace {

namespace mat = materials;

class ReducedOrderProgram : public ::testing::Test {
protected:
  void SetUp() override { test::addReducedOrderEntry(lib_, "polyurea-cell", model_); }
  test::RunResult run(const std::string& args) { return test::runMaterials(dir_, lib_, args); }
  test::TempDir dir_;
  std::filesystem::path lib_ = dir_.path() / "library.toml";
  mat::ReducedOrderModel model_ = test::polyureaLaminate(true);
};

// The program's CSV equals drive() of the law built directly from the cell
// (17 significant digits read back: exactly), with the header and row count
// of a polyurea-gvbo run; in finite kinematics (rotations: shear) and small.
TEST_F(ReducedOrderProgram, DriveGivesTheStressOfTheLawBuiltDirectly) {
  const mat::ReducedOrderLaw law("polyurea-cell", model_);
  for (const char* kin : {"finite", "small"}) {
    const auto csv = dir_.path() / (std::string("cell-") + kin + ".csv");
    const auto gvbo = dir_.path() / (std::string("gvbo-") + kin + ".csv");
    const std::string common =
        " --path shear --rate 1e2 --to 0.3 --steps 30 --unload --kinematics " + std::string(kin);
    auto r = run("drive polyurea-cell" + common + " --out '" + csv.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("(reduced-order)"), std::string::npos) << r.err;
    ASSERT_EQ(run("drive polyurea-gvbo" + common + " --out '" + gvbo.string() + "'").status, 0);
    std::string header, gvbo_header;
    const auto rows = test::readCsvRows(csv, &header);
    EXPECT_EQ(rows.size(), test::readCsvRows(gvbo, &gvbo_header).size());
    EXPECT_EQ(header, gvbo_header);
    mat::DriveOptions o;
    o.path = mat::DrivePath::Shear;
    o.rate = 1e2;
    o.to = 0.3;
    o.steps = 30;
    o.unload = true;
    o.kinematics = std::string(kin) == "small" ? mat::Kinematics::Small : mat::Kinematics::Finite;
    const auto expect = mat::drive(law, o);
    ASSERT_EQ(rows.size(), expect.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (int k = 0; k < 6; ++k)
        EXPECT_EQ(rows[i][static_cast<std::size_t>(7 + k)], expect[i].sigma[k])
            << kin << " row " << i;
  }
}

// --nonlinear-dispersion: one row per step with t, the 21 upper-triangle
// components and max_ratio; in small kinematics (no rotation) max_ratio is
// the largest |component| over max |D_lin| = 1e-6 kg/m of the test cell,
// and the first rows (nearly elastic at 1e4 /s) differ from the last (flow).
TEST_F(ReducedOrderProgram, NonlinearDispersionAlongTheHistory) {
  const auto csv = dir_.path() / "c.csv", disp = dir_.path() / "d.csv";
  const auto r = run("drive polyurea-cell --path confined --rate 1e1 --to 0.2 --steps 20 "
                     "--kinematics small --out '" +
                     csv.string() + "' --nonlinear-dispersion '" + disp.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  const auto rows = test::readCsvRows(disp, &header);
  EXPECT_EQ(header.substr(0, 15), "t,D11,D12,D13,D");
  EXPECT_EQ(header.substr(header.size() - 14), ",D66,max_ratio");
  ASSERT_EQ(rows.size(), 20u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 23u);
    EXPECT_DOUBLE_EQ(rows[i][0], 0.2 / 1e1 * static_cast<double>(i + 1) / 20);
    double largest = 0;
    for (std::size_t k = 1; k <= 21; ++k)
      largest = std::max(largest, std::abs(rows[i][k]));
    EXPECT_DOUBLE_EQ(rows[i][22], largest / 1e-6) << "row " << i;
  }
  EXPECT_GT(rows.back()[22], 0.0);
}

// show: per phase its partitions (1 each), the state of the documented
// layout (GVBO 6 + 20, elastic 6 + 0 = 32 doubles), the side file; --json the
// same numbers; list names the kind and the phases; export --format json has
// the phases.
TEST_F(ReducedOrderProgram, ShowListAndExportDescribeTheEntry) {
  auto r = run("show polyurea-cell");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(reduced-order)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("soft  gvbo"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1100 kg/m^3  1 partition\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("state 32 doubles per point"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("side file library.side/polyurea-cell."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("side checksum fnv1a64:"), std::string::npos) << r.out;
  r = run("show polyurea-cell --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("state_doubles").get<int>(), 32);
  EXPECT_EQ(j.at("nonlinear_partitions").get<int>(), 1);
  EXPECT_EQ(j.at("phases").at(0).at("partitions").get<int>(), 1);
  EXPECT_EQ(j.at("phases").at(1).at("partitions").get<int>(), 1);
  EXPECT_EQ(j.at("phases").at(0).at("gvbo").at("k1").get<double>(), 17.0);
  r = run("list");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("polyurea-cell  reduced-order"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("phases soft (gvbo), hard (anisotropic)"), std::string::npos) << r.out;
  r = run("export polyurea-cell --format json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).at("phases").size(), 2u);
}

} // namespace
} // namespace lamina
