/// @file malformed_arguments_test.cpp
/// @brief Hostile command lines of `homogenize --path / --tangent-rates`,
/// `materials drive`, `micro` and `membrane`: errors inside the solver's
/// parallel regions, absurd rates, outputs that are devices, FIFOs,
/// directories or inputs of the run, a strain path without its rate, and
/// several entries whose names collide. Each ends in exit 1 (2 for a CLI
/// error) with a message naming the argument, and nothing is replaced.

#include "program.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

using namespace lamina::test;

namespace {

/// A fresh folder per test, with a FIFO, a symlink to /dev/null and a
/// directory in it (the outputs that are not regular files).
class Arguments : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = freshTestDir("lamina_arguments");
    fs::create_directories(dir_ / "folder.csv");
    ASSERT_EQ(::mkfifo((dir_ / "fifo.csv").c_str(), 0644), 0);
    fs::create_symlink("/dev/null", dir_ / "null.csv");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string bin(const std::string& program) const { return (kBin / program).string(); }
  std::string at(const std::string& name) const { return "'" + (dir_ / name).string() + "'"; }
  /// The polyurea cell at 4^3 voxels: a GVBO matrix, cheap to run.
  std::string homogenize() const {
    return bin("homogenize") + " " + (kCases / "cells/polyurea.toml").string() +
           " --resolution 4 --quiet";
  }
  /// Makes lib.toml holding catalog entry e-glass as @p entry; @return its text.
  std::string libraryWith(const std::string& entry) const {
    const Result r = run(bin("materials") + " --library " + at("lib.toml") + " add " + entry +
                         " --from-catalog e-glass");
    EXPECT_EQ(r.code, 0) << r.output;
    return slurp(dir_ / "lib.toml");
  }
  /// The non-regular outputs are still what they were.
  void expectNodesIntact() const {
    struct stat st {};
    ASSERT_EQ(::stat((dir_ / "fifo.csv").c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
    EXPECT_TRUE(fs::is_symlink(dir_ / "null.csv"));
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    EXPECT_TRUE(fs::is_directory(dir_ / "folder.csv"));
  }
  fs::path dir_;
};

} // namespace

// A GVBO update refusing a state inside the solver's OpenMP region aborted
// the process (exit 134); so did a denormal tangent rate. Now: exit 1 and
// the reason, no output file.
TEST_F(Arguments, ErrorsInsideTheSolverAndAbsurdRatesAreCleanErrors) {
  Result r =
      run(homogenize() + " --path confined --rate 1e4 --to 1 --steps 2 --out " + at("x.csv"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--to"), std::string::npos) << r.output;
  r = run(homogenize() + " --path confined --rate 1e4 --to 0.999 --steps 1 --out " + at("x.csv"));
  EXPECT_EQ(r.code, 1) << r.output; // the law refuses J = 0.001 on the solver's threads
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
  for (const std::string rates : {"1e-320", "1e13", "1e-13", "nan", "1e5,-inf"}) {
    r = run(homogenize() + " --name x --library " + at("l.toml") + " --tangent-rates=" + rates);
    EXPECT_EQ(r.code, 1) << rates << ": " << r.output;
    EXPECT_NE(r.output.find("--tangent-rates"), std::string::npos) << rates << ": " << r.output;
  }
  // the increment and the state of a tangent: a strain increment in (0, 1],
  // a confined state below a compression of 1
  r = run(homogenize() + " --name x --library " + at("l.toml") +
          " --tangent-rates 1e5 --tangent-increment 2");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--tangent-increment"), std::string::npos) << r.output;
  r = run(homogenize() + " --name x --library " + at("l.toml") +
          " --tangent-rates 1e5 --tangent-strain 1 --path confined");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--tangent-strain"), std::string::npos) << r.output;
  r = run(bin("materials") + " drive polyurea-gvbo --rate 1e-320 --to 0.1 --out " + at("d.csv"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--rate"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "l.toml"));
  EXPECT_FALSE(fs::exists(dir_ / "d.csv"));
}

// --out naming a FIFO, a symlink to a device or a directory replaced the
// node with a regular file; --out naming the library overwrote it with a
// CSV. Now each is refused before anything runs.
TEST_F(Arguments, OutputsReplaceOnlyRegularFilesThatAreNotInputs) {
  const fs::path lib = dir_ / "lib.toml";
  const std::string library = libraryWith("glass");
  Result r{0, ""};
  const std::string drive = bin("materials") + " --library " + at("lib.toml") +
                            " drive polyurea-gvbo --path shear --rate 1e3 --to 0.01 --steps 2 ";
  const std::string path_run = homogenize() + " --path shear --rate 1e4 --to 0.01 --steps 1 ";
  const std::string micro =
      bin("micro") + " " + (kCases / "cells/sphere.toml").string() + " --resolution 4 --out ";
  for (const std::string node : {"fifo.csv", "null.csv", "folder.csv"}) {
    for (const std::string& cmd : {drive + "--out " + at(node), path_run + "--out " + at(node)}) {
      r = run(cmd);
      EXPECT_EQ(r.code, 1) << cmd << "\n" << r.output;
      EXPECT_NE(r.output.find("refusing to write over"), std::string::npos) << r.output;
    }
  }
  // micro: an .h5 output that is a FIFO
  ASSERT_EQ(::mkfifo((dir_ / "map.h5").c_str(), 0644), 0);
  r = run(micro + at("map.h5"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("a FIFO"), std::string::npos) << r.output;
  expectNodesIntact();
  // the library, the cell, a symlink to the library
  fs::create_symlink(lib, dir_ / "link.csv");
  for (const std::string& cmd :
       {drive + "--out " + at("lib.toml"), drive + "--out " + at("link.csv"),
        path_run + "--library " + at("lib.toml") + " --out " + at("link.csv"),
        path_run + "--out '" + (kCases / "cells/polyurea.toml").string() + "'"}) {
    r = run(cmd);
    EXPECT_EQ(r.code, 1) << cmd << "\n" << r.output;
    EXPECT_NE(r.output.find("is an input of the run"), std::string::npos) << cmd << r.output;
  }
  EXPECT_EQ(slurp(lib), library); // byte for byte
  // membrane: --out naming a file (the case itself) is not a folder
  const fs::path case_file = kCases / "membrane/case1.toml";
  if (fs::exists(case_file)) {
    r = run(bin("membrane") + " run '" + case_file.string() + "' --out '" + case_file.string() +
            "'");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
  }
}

// One rule for both programs: a strain path needs its rate and its final
// strain; homogenize ran at an undocumented 1e4 /s to 0.1 without them.
TEST_F(Arguments, StrainPathNeedsRateAndFinalStrainInBothPrograms) {
  const std::string out = " --steps 1 --out " + at("x.csv");
  Result r = run(homogenize() + " --path shear --to 0.05" + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--rate"), std::string::npos) << r.output;
  r = run(homogenize() + " --path shear --rate 1e4" + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--to"), std::string::npos) << r.output;
  r = run(homogenize() + " --name x --library " + at("l.toml") + " --rate 1e4 --to 0.1");
  EXPECT_EQ(r.code, 2) << r.output; // without --path they would be ignored
  EXPECT_NE(r.output.find("--rate"), std::string::npos) << r.output;
  r = run(bin("materials") + " drive polyurea-gvbo --path shear --to 0.05" + out);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--rate"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "l.toml"));
}

// Entries whose names collide (two rates printing alike, two J states
// printing alike, a name already in the library) are refused before
// anything is computed: the library is unchanged, not one entry added.
TEST_F(Arguments, SeveralEntriesWithCollidingNamesAddNothing) {
  const fs::path lib = dir_ / "lib.toml";
  const std::string library = libraryWith("x-J0.9");
  Result r{0, ""};
  const std::string sweep = (dir_ / "sweep.toml").string();
  std::string cell = slurp(kCases / "cells/polyurea-sweep.toml");
  write(sweep, cell);
  const std::string base = bin("homogenize") + " '" + sweep + "' --resolution 4 --quiet --name x " +
                           "--library " + at("lib.toml");
  r = run(base); // x-J0.9 exists
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("'x-J0.9' is already in library"), std::string::npos) << r.output;
  cell.replace(cell.find("J = [1.0, 0.95, 0.9]"), 20, "J = [0.95, 0.9500001]");
  write(sweep, cell);
  r = run(base); // both print as x-J0.95
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("'x-J0.95'"), std::string::npos) << r.output;
  r = run(homogenize() + " --name y --library " + at("lib.toml") + " --tangent-rates 1e5,100000");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("'y-R100000'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--tangent-rates"), std::string::npos) << r.output;
  EXPECT_EQ(slurp(lib), library);
  EXPECT_FALSE(fs::exists(dir_ / "lib.side"));
}
