// Bad command lines of `homogenize --reduced-order`: each exits 1 (a
// lamina::Error) or 2 (a command-line error) with a message that names the
// option, and leaves the library byte for byte as it was (no side folder
// either).

#include "core/error.hpp"
#include "homogenize/cli.hpp"
#include "materials/library.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace lamina::test {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A 6^3 cell: a sphere of 'bead' (27 voxels) in 'matrix'.
constexpr const char* kCell = R"([cell]
resolution = 6
size = 1e-3

[[phases]]
name = "matrix"
law = "isotropic"
E = 3e9
nu = 0.4
density = 1100.0

[[phases]]
name = "bead"
law = "isotropic"
E = 70e9
nu = 0.25
density = 2700.0

[[inclusions]]
phase = "bead"
shape = "sphere"
radius = 0.3e-3
placement = "single"
)";

class MalformedReducedOrder : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lamina_ro_args_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "cell.toml") << kCell;
    materials::Library lib(dir_ / "lib.toml"); // one entry already there
    materials::Material m;
    m.name = "steel";
    m.C = materials::Stiffness::isotropic(210e9, 0.3);
    m.density = 7800;
    lib.add(m);
    before_ = slurp(dir_ / "lib.toml");
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Runs `homogenize cell.toml --library lib.toml ARGS`: exit code, stderr.
  std::pair<int, std::string> run(const std::vector<std::string>& args, const fs::path& cell = {}) {
    std::vector<std::string> all{"homogenize",
                                 cell.empty() ? (dir_ / "cell.toml").string() : cell.string(),
                                 "--library", (dir_ / "lib.toml").string(), "--quiet"};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    int argc = static_cast<int>(all.size());
    char** pargv = argv.data();
    homogenize::MpiSession mpi(&argc, &pargv);
    ::testing::internal::CaptureStderr();
    ::testing::internal::CaptureStdout();
    const int code = homogenize::runProgram(argc, pargv, mpi);
    const std::string err = ::testing::internal::GetCapturedStderr();
    const std::string out = ::testing::internal::GetCapturedStdout();
    return {code, err + out};
  }

  /// The library is as it was and no side file was written.
  void expectUnchanged() {
    EXPECT_EQ(slurp(dir_ / "lib.toml"), before_);
    EXPECT_FALSE(fs::exists(dir_ / "lib.side"));
  }

  fs::path dir_;
  std::string before_;
};

TEST_F(MalformedReducedOrder, ZeroPartitionsIsAUsageError) {
  const auto [code, msg] = run({"--name", "ro", "--reduced-order", "--partitions", "0"});
  EXPECT_EQ(code, kExitUsage) << msg;
  EXPECT_NE(msg.find("--partitions"), std::string::npos) << msg;
  expectUnchanged();
}

TEST_F(MalformedReducedOrder, MorePartitionsThanAPhaseHasVoxels) {
  const auto [code, msg] = run({"--name", "ro", "--reduced-order", "--partitions", "100"});
  EXPECT_EQ(code, kExitUserError) << msg;
  EXPECT_NE(msg.find("--partitions"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'bead'"), std::string::npos) << msg; // the phase with too few voxels
  expectUnchanged();
}

TEST_F(MalformedReducedOrder, NotWithAStrainPathNorTangentRates) {
  auto [code, msg] = run({"--name", "ro", "--reduced-order", "--path", "shear"});
  EXPECT_EQ(code, kExitUsage) << msg;
  EXPECT_NE(msg.find("--reduced-order"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--path"), std::string::npos) << msg;
  expectUnchanged();
  std::tie(code, msg) = run({"--name", "ro", "--reduced-order", "--tangent-rates", "1e4"});
  EXPECT_EQ(code, kExitUsage) << msg;
  EXPECT_NE(msg.find("--reduced-order"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--tangent-rates"), std::string::npos) << msg;
  expectUnchanged();
}

TEST_F(MalformedReducedOrder, PartitionOptionsOnlyWithReducedOrder) {
  auto [code, msg] = run({"--name", "x", "--partitions", "2"});
  EXPECT_EQ(code, kExitUsage) << msg;
  EXPECT_NE(msg.find("--partitions"), std::string::npos) << msg;
  std::tie(code, msg) = run({"--name", "x", "--reduced-order", "--partition-seed", "3"});
  EXPECT_EQ(code, kExitUsage) << msg;
  EXPECT_NE(msg.find("--partition-seed"), std::string::npos) << msg;
  std::tie(code, msg) = run({"--name", "x", "--scheme", "clustering"});
  EXPECT_EQ(code, kExitUsage) << msg;
  EXPECT_NE(msg.find("--scheme"), std::string::npos) << msg;
  expectUnchanged();
}

TEST_F(MalformedReducedOrder, UnknownSchemeIsAUsageError) {
  const auto [code, msg] = run({"--name", "ro", "--reduced-order", "--scheme", "sca"});
  EXPECT_EQ(code, kExitUsage) << msg;
  EXPECT_NE(msg.find("--scheme"), std::string::npos) << msg;
  EXPECT_NE(msg.find("clustering"), std::string::npos) << msg; // the choices are named
  expectUnchanged();
}

TEST_F(MalformedReducedOrder, NameMissingOrTaken) {
  auto [code, msg] = run({"--reduced-order"});
  EXPECT_EQ(code, kExitUserError) << msg;
  EXPECT_NE(msg.find("--name"), std::string::npos) << msg;
  std::tie(code, msg) = run({"--reduced-order", "--name", "steel"});
  EXPECT_EQ(code, kExitUserError) << msg;
  EXPECT_NE(msg.find("--name"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'steel'"), std::string::npos) << msg;
  expectUnchanged();
}

// A yarn that follows its path rotates its phase voxel by voxel: the phase
// has no single reference stiffness, and the build is refused before any
// solve, naming the cell file and the phase.
TEST_F(MalformedReducedOrder, CellWithOrientedYarnsIsRefused) {
  const fs::path cell = fs::path(LAMINA_SOURCE_DIR) / "cases/cells/plain-weave-ti.toml";
  const auto [code, msg] = run({"--name", "ro", "--reduced-order", "--resolution", "8"}, cell);
  EXPECT_EQ(code, kExitUserError) << msg;
  EXPECT_NE(msg.find("plain-weave-ti.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("follows its yarn's path"), std::string::npos) << msg;
  expectUnchanged();
}

} // namespace
} // namespace lamina::test
