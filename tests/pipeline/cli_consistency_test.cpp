/// @file cli_consistency_test.cpp
/// @brief One command-line interface, not four: the built programs (micro,
/// homogenize, materials, membrane) take the shared options (--library,
/// --catalog, --set, --threads, --json, --quiet) in the same places, before
/// or after a subcommand, with the same help line in every --help; a
/// missing subcommand gets one message; --set on a cell file changes the
/// cell that is built.

#include "program.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <map>
#include <regex>
#include <set>

using namespace lamina::test;

namespace {

/// The shared options.
const std::vector<std::string> kShared = {"--library", "--catalog", "--set",
                                          "--threads", "--json",    "--quiet"};

/// Every help screen: the program and, for a program with subcommands, each
/// subcommand ("" = the program's own --help).
const std::vector<std::pair<std::string, std::string>> kScreens = {
    {"micro", ""},           {"homogenize", ""},        {"materials", ""},
    {"materials", "list"},   {"materials", "show"},     {"materials", "add"},
    {"materials", "layup"},  {"materials", "export"},   {"materials", "remove"},
    {"materials", "drive"},  {"membrane", ""},          {"membrane", "run"},
    {"membrane", "converge"}, {"membrane", "blast"}};

/// Which screens list each shared option: where it applies (the program's
/// own screen lists every option one of its subcommands takes).
const std::map<std::string, std::set<std::string>> kWhere = {
    {"--library",
     {"homogenize", "materials", "materials list", "materials show", "materials add",
      "materials layup", "materials export", "materials remove", "materials drive", "membrane",
      "membrane run", "membrane converge"}},
    {"--catalog",
     {"micro", "homogenize", "materials", "materials list", "materials show", "materials add",
      "materials layup", "materials export", "materials remove", "materials drive", "membrane",
      "membrane run", "membrane converge"}},
    {"--set", {"micro", "homogenize", "membrane", "membrane run", "membrane converge"}},
    {"--threads", {"micro", "homogenize", "membrane", "membrane run", "membrane converge"}},
    {"--json",
     {"micro", "homogenize", "materials", "materials list", "materials show", "membrane",
      "membrane run", "membrane converge", "membrane blast"}},
    {"--quiet", {"homogenize", "membrane", "membrane run", "membrane converge"}}};

std::string bin(const std::string& program) {
  return (kBin / program).string();
}

/// @return the help line of each shared option on @p help, spaces collapsed
/// (CLI11 aligns the columns per screen)
std::map<std::string, std::string> sharedLines(const std::string& help) {
  std::map<std::string, std::string> out;
  std::istringstream in(help);
  std::string line;
  while (std::getline(in, line)) {
    const std::string flat =
        std::regex_replace(std::regex_replace(line, std::regex("^\\s+"), ""),
                           std::regex("\\s+"), " ");
    for (const auto& o : kShared)
      if (flat.rfind(o + " ", 0) == 0 || flat == o)
        out[o] = flat;
  }
  return out;
}

class CommandLine : public ::testing::Test {
protected:
  void SetUp() override {
    for (const auto* p : {"micro", "homogenize", "materials", "membrane"})
      if (!have(p))
        GTEST_SKIP() << p << " not built";
    dir_ = freshTestDir("lamina_cli");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string at(const std::string& name) const { return "'" + (dir_ / name).string() + "'"; }
  fs::path dir_;
};

// Each shared option has one help line (text, value name, default) in every
// --help that lists it, and is listed exactly where it applies: on each
// subcommand that takes it and on the program before the subcommand.
TEST_F(CommandLine, SharedOptionsHaveOneHelpLineEverywhere) {
  std::map<std::string, std::map<std::string, std::string>> lines; // option -> screen -> line
  for (const auto& [program, sub] : kScreens) {
    const std::string screen = sub.empty() ? program : program + " " + sub;
    const Result r = run(bin(program) + (sub.empty() ? "" : " " + sub) + " --help");
    ASSERT_EQ(r.code, 0) << screen << ": " << r.output;
    for (const auto& [option, line] : sharedLines(r.output))
      lines[option][screen] = line;
  }
  for (const auto& o : kShared) {
    std::set<std::string> screens;
    for (const auto& [screen, line] : lines[o])
      screens.insert(screen);
    EXPECT_EQ(screens, kWhere.at(o)) << o;
    const std::string first = lines[o].begin()->second;
    for (const auto& [screen, line] : lines[o])
      EXPECT_EQ(line, first) << o << " on " << screen;
  }
  // the one wording of the defaults, as README and docs/materials.md say
  EXPECT_NE(lines["--library"]["materials"].find(
                "--library PATH, else $LAMINA_LIBRARY, else $XDG_DATA_HOME/lamina/library.toml"),
            std::string::npos);
  EXPECT_NE(lines["--catalog"]["micro"].find("else $LAMINA_CATALOG"), std::string::npos);
  EXPECT_NE(lines["--threads"]["micro"].find("=0"), std::string::npos); // its default shown
}

// Options with a default show it in --help (CLI11 "=VALUE" after the type).
TEST_F(CommandLine, HelpShowsTheDefaults) {
  const Result h = run(bin("homogenize") + " --help");
  EXPECT_NE(h.output.find("--tol FLOAT:POSITIVE=1e-05"), std::string::npos) << h.output;
  EXPECT_NE(h.output.find("--steps INT:INT in [1 - 10000000]=100"), std::string::npos);
  EXPECT_NE(h.output.find("--fftw-plan TEXT:{auto,estimate,measure}=auto"), std::string::npos);
  const Result e = run(bin("materials") + " export --help");
  EXPECT_NE(e.output.find("=json"), std::string::npos) << e.output;
  const Result m = run(bin("materials") + " --help");
  EXPECT_NE(m.output.find("drive"), std::string::npos) << m.output; // the summary lists drive
  EXPECT_NE(m.output.find("list, show, add, layup, export, remove, drive"), std::string::npos);
}

// Before or after the subcommand: the same command, the same result.
TEST_F(CommandLine, SharedOptionsGoBeforeOrAfterTheSubcommand) {
  const std::string lib = at("lib.toml");
  ASSERT_EQ(run(bin("materials") + " add t1 --from-catalog table1-anisotropic --library " + lib)
                .code,
            0);
  const Result before = run(bin("materials") + " --library " + lib + " list");
  const Result after = run(bin("materials") + " list --library " + lib);
  EXPECT_EQ(before.code, 0) << before.output;
  EXPECT_EQ(after.code, 0) << after.output;
  EXPECT_EQ(before.output, after.output);
  EXPECT_EQ(before.output.rfind("t1  ", 0), 0u) << before.output;
  const Result json_before = run(bin("materials") + " --json --library " + lib + " list");
  const Result json_after = run(bin("materials") + " list --library " + lib + " --json");
  EXPECT_EQ(json_before.output, json_after.output);
  EXPECT_EQ(nlohmann::json::parse(json_after.output).at(0).at("name"), "t1");
  const std::string blast = " blast --charge 10 --distance 4.4";
  const Result b1 = run(bin("membrane") + " --json" + blast);
  const Result b2 = run(bin("membrane") + blast + " --json");
  EXPECT_EQ(b1.code, 0) << b1.output;
  EXPECT_EQ(b1.output, b2.output);
  EXPECT_TRUE(nlohmann::json::accept(b1.output)) << b1.output;
  // an option before the subcommand that the subcommand does not take
  const Result refused = run(bin("materials") + " --json --library " + lib + " remove t1");
  EXPECT_EQ(refused.code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--json: 'materials remove' does not take it"), std::string::npos)
      << refused.output;
  EXPECT_EQ(run(bin("materials") + " list --library " + lib).output, before.output); // kept
}

// A missing subcommand: the same message in every program that has them.
TEST_F(CommandLine, MissingSubcommandHasOneMessage) {
  const Result m = run(bin("materials"));
  const Result b = run(bin("membrane"));
  EXPECT_EQ(m.code, 2);
  EXPECT_EQ(b.code, 2);
  EXPECT_EQ(m.output, "materials: error: a subcommand is required: one of list, show, add, layup, "
                      "export, remove, drive (see materials --help)\n");
  EXPECT_EQ(b.output, "membrane: error: a subcommand is required: one of run, converge, blast "
                      "(see membrane --help)\n");
}

// --set on a cell file changes the cell built: micro writes 8^3 labels
// instead of the file's 32^3 (a .raw file holds one label per voxel, so its
// size scales by (32/8)^3 = 64), and homogenize solves on 8^3 voxels and
// records the --set in the entry's provenance.
TEST_F(CommandLine, SetOnACellFileChangesTheCell) {
  const std::string cell = (kCases / "cells/sphere.toml").string();
  const Result small = run(bin("micro") + " " + cell + " --set cell.resolution=8 --json --out " +
                           at("small.raw"));
  ASSERT_EQ(small.code, 0) << small.output;
  const auto j = nlohmann::json::parse(small.output);
  EXPECT_EQ(j.at("voxels"), nlohmann::json::array({8, 8, 8}));
  const Result full = run(bin("micro") + " " + cell + " --quiet --out " + at("full.raw"));
  EXPECT_EQ(full.code, 2) << full.output; // micro has no progress line: no --quiet
  ASSERT_EQ(run(bin("micro") + " " + cell + " --out " + at("full.raw")).code, 0);
  EXPECT_EQ(fs::file_size(dir_ / "full.raw"), 64 * fs::file_size(dir_ / "small.raw"));
  const Result h = run(bin("homogenize") + " " + cell + " --name s8 --quiet --json --library " +
                       at("lib.toml") + " --set cell.resolution=8");
  ASSERT_EQ(h.code, 0) << h.output;
  const std::string first_line = h.output.substr(0, h.output.find('\n'));
  EXPECT_EQ(nlohmann::json::parse(first_line).at("voxels"), 512) << h.output;
  const std::string library = slurp(dir_ / "lib.toml");
  const auto overrides = library.find("cell_overrides");
  ASSERT_NE(overrides, std::string::npos) << library;
  EXPECT_NE(library.find("cell.resolution=8", overrides), std::string::npos) << library;
}

} // namespace
