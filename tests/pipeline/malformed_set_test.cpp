/// @file malformed_set_test.cpp
/// @brief A bad `--set KEY=VALUE` is the command line's fault, not the
/// file's: in membrane (case files), micro and homogenize (cell files) the
/// error names the --set and the key, and does not blame the file.

#include "program.hpp"

#include <gtest/gtest.h>

using namespace lamina::test;

namespace {

class BadSet : public ::testing::Test {
protected:
  void SetUp() override { dir_ = freshTestDir("lamina_bad_set"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string bin(const std::string& program) const { return (kBin / program).string(); }
  /// Expects exit 1 and a message naming "--set ASSIGNMENT" and 'KEY', not
  /// "FILE:" (the file did nothing wrong).
  void expectBlamesSet(const std::string& command, const std::string& assignment,
                       const std::string& key, const std::string& file) const {
    const Result r = run(command);
    EXPECT_EQ(r.code, 1) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("--set " + assignment + ": '" + key + "'"), std::string::npos)
        << command << "\n" << r.output;
    EXPECT_EQ(r.output.find(file + ":"), std::string::npos) << command << "\n" << r.output;
  }
  fs::path dir_;
};

TEST_F(BadSet, MembraneNamesTheSetNotTheCaseFile) {
  if (!have("membrane"))
    GTEST_SKIP() << "membrane not built";
  const std::string c = (kCases / "membrane/case3.toml").string();
  const std::string out = " --out '" + (dir_ / "out").string() + "'";
  expectBlamesSet(bin("membrane") + " run " + c + out + " --set time.dt=abc", "time.dt=abc",
                  "time.dt", "case3.toml");
  // before the subcommand: the same option, the same message
  expectBlamesSet(bin("membrane") + " --set time.dt=abc run " + c + out, "time.dt=abc", "time.dt",
                  "case3.toml");
  expectBlamesSet(bin("membrane") + " converge " + c + " --levels 3 --set mesh.nx=[1]",
                  "mesh.nx=[1]", "mesh.nx", "case3.toml");
  expectBlamesSet(bin("membrane") + " run " + c + out + " --set time.bogus=1", "time.bogus=1",
                  "time.bogus", "case3.toml");
}

TEST_F(BadSet, MicroAndHomogenizeNameTheSetNotTheCellFile) {
  if (!have("micro") || !have("homogenize"))
    GTEST_SKIP() << "micro or homogenize not built";
  const std::string cell = (kCases / "cells/sphere.toml").string();
  const std::string micro = bin("micro") + " " + cell + " --out '" + (dir_ / "p.h5").string() + "'";
  expectBlamesSet(micro + " --set cell.resolution=abc", "cell.resolution=abc", "cell.resolution",
                  "sphere.toml");
  expectBlamesSet(micro + " --set 'phases[0].E=\"soft\"'", "phases[0].E=\"soft\"", "phases[0].E",
                  "sphere.toml");
  expectBlamesSet(micro + " --set cell.colour=1", "cell.colour=1", "cell.colour", "sphere.toml");
  const std::string homogenize = bin("homogenize") + " " + cell + " --name x --library '" +
                                 (dir_ / "lib.toml").string() + "'";
  expectBlamesSet(homogenize + " --set cell.resolution=abc", "cell.resolution=abc",
                  "cell.resolution", "sphere.toml");
  EXPECT_FALSE(fs::exists(dir_ / "lib.toml"));
  EXPECT_FALSE(fs::exists(dir_ / "p.h5"));
}

} // namespace
