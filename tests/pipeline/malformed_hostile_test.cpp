/// @file malformed_hostile_test.cpp
/// @brief Reproducers of hostile input run through the programs as a user would:
/// each used to crash (stack overflow, OpenMP), escape its folder or leave
/// a half-written output folder; now each gives a clean error naming the
/// cause, or (for a signal) complete outputs and the shell's exit code.

#include "../core/test_util.hpp"
#include "core/hdf5_file.hpp"
#include "program.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>

using namespace lamina::test;

namespace {

/// A fresh folder per test.
class Hostile : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lamina_hostile_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string bin(const std::string& program) const { return (kBin / program).string(); }
  fs::path dir_;
};

} // namespace

// A key of 50000 dots overflowed the stack in all four programs (exit 139).
TEST_F(Hostile, DeepTomlIsRefusedByEveryProgram) {
  const fs::path d = dir_ / "d.toml";
  write(d, "a" + repeat(".a", 50000) + " = 1\n");
  const std::vector<std::string> commands{
      bin("materials") + " --library '" + d.string() + "' list",
      bin("membrane") + " run '" + d.string() + "' --out '" + (dir_ / "o").string() + "'",
      bin("homogenize") + " '" + d.string() + "' --name x --library '" +
          (dir_ / "lib.toml").string() + "'",
      bin("micro") + " '" + d.string() + "' --out '" + (dir_ / "x.h5").string() + "'"};
  for (const auto& cmd : commands) {
    const Result r = run(cmd);
    EXPECT_EQ(r.code, 1) << cmd << "\n" << r.output;
    EXPECT_NE(r.output.find(d.string() + ":1"), std::string::npos) << r.output;
  }
}

// --threads 100000 crashed inside OpenMP; `--name ../../x` wrote outside
// the library's folder.
TEST_F(Hostile, HomogenizeRefusesThreadsAndNamesBeforeWorking) {
  const std::string base = bin("homogenize") + " " + (kCases / "cells/sphere.toml").string() +
                           " --resolution 8 --quiet --library '" +
                           (dir_ / "a/b/lib.toml").string() + "'";
  Result r = run(base + " --name t --threads 100000");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--threads"), std::string::npos) << r.output;
  for (const std::string name : {"../../x", "/tmp/x", "a\\;b"}) {
    r = run(base + " --name '" + name + "'");
    EXPECT_EQ(r.code, 1) << name << ": " << r.output;
    EXPECT_NE(r.output.find("--name"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.h5"));
  EXPECT_FALSE(fs::exists(dir_ / "a"));
}

// SIGINT and SIGTERM: the run finishes its step, renames its CSVs into
// place, writes summary.json with "interrupted": true and exits with the
// shell's code for the signal (128 + 2, 128 + 15).
TEST_F(Hostile, InterruptedRunLeavesCompleteOutputs) {
  for (const int sig : {SIGINT, SIGTERM}) {
    const fs::path out = dir_ / ("out" + std::to_string(sig));
    // Case 3 run for 10^5 steps: minutes, so the signal comes mid-run.
    const pid_t pid =
        spawn({bin("membrane"), "run", (kCases / "membrane/case3.toml").string(), "--out",
               out.string(), "--set", "time.t_end=1.0", "--set", "output.field_every=1000"});
    ASSERT_GT(pid, 0);
    for (int i = 0; i < 6000 && !fs::exists(out / "probes.csv.part"); ++i)
      ::usleep(10000); // started stepping (generous on a loaded machine)
    ::usleep(200000);
    ::kill(pid, sig);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping";
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    const std::string summary = slurp(out / "summary.json");
    EXPECT_NE(summary.find("\"interrupted\": true"), std::string::npos) << summary;
    for (const auto& f : fs::directory_iterator(out))
      EXPECT_NE(f.path().extension(), ".part") << f.path();
    // One probe row per step taken, plus t = 0, and nothing torn.
    const std::string probes = slurp(out / "probes.csv");
    ASSERT_FALSE(probes.empty());
    EXPECT_EQ(probes.back(), '\n');
  }
}
