// The strict TOML reader on valid input: values of every type come back as
// written, defaults apply only when a key is absent, finish() accepts a
// document whose every key was read, and command-line overrides set nested
// keys with TOML-typed values.

#include "core/error.hpp"
#include "core/toml_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace core = lamina::core;

namespace {

const char* kCase = R"(title = "impact"
steps = 200
[solver]
tolerance = 1e-8
max_iterations = 50
verbose = true
[mesh]
size = [0.5, 0.25, 1]
names = ["a", "b"]
C = [[1, 2.5], [3, 4]]
[[loads]]
kind = "point"
magnitude = 10.0
[[loads]]
kind = "pressure"
magnitude = 2
[provenance]
anything = { goes = "here", n = 3 }
)";

} // namespace

TEST(TableReader, ReadsEveryTypeAsWritten) {
  const toml::table doc = core::parseTomlString(kCase, "case.toml");
  const core::TableReader root(doc, "case.toml");
  EXPECT_EQ(root.getString("title"), "impact");
  EXPECT_EQ(root.getInt("steps"), 200);
  EXPECT_EQ(root.getDouble("steps", 0.0), 200.0); // an integer is a number too
  const core::TableReader solver = root.table("solver");
  EXPECT_EQ(solver.getDouble("tolerance"), 1e-8);
  EXPECT_EQ(solver.getInt("max_iterations", 7), 50);
  EXPECT_TRUE(solver.getBool("verbose", false));
  const core::TableReader mesh = root.table("mesh");
  EXPECT_EQ(mesh.getDoubleArray("size"), (std::vector<double>{0.5, 0.25, 1.0}));
  EXPECT_EQ(mesh.getStringArray("names"), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(mesh.getMatrix("C"), (std::vector<std::vector<double>>{{1, 2.5}, {3, 4}}));
  const auto loads = root.tableArray("loads");
  ASSERT_EQ(loads.size(), 2u);
  EXPECT_EQ(loads[0].getString("kind"), "point");
  EXPECT_EQ(loads[0].getDouble("magnitude"), 10.0);
  EXPECT_EQ(loads[1].getString("kind"), "pressure");
  EXPECT_EQ(loads[1].getDouble("magnitude"), 2.0);
  EXPECT_EQ(loads[1].path("magnitude"), "loads[1].magnitude");
  EXPECT_NE(root.raw("provenance"), nullptr);
  EXPECT_NO_THROW(root.finish());
}

TEST(TableReader, DefaultsApplyOnlyWhenAbsent) {
  const toml::table doc = core::parseTomlString("a = 1.5\n", "x.toml");
  const core::TableReader root(doc, "x.toml");
  EXPECT_EQ(root.getDouble("a", 9.0), 1.5);
  EXPECT_EQ(root.getDouble("b", 9.0), 9.0);
  EXPECT_EQ(root.getInt("n", -3), -3);
  EXPECT_EQ(root.getString("s", "dflt"), "dflt");
  EXPECT_FALSE(root.getBool("flag", false));
  EXPECT_FALSE(root.optionalTable("t").has_value());
  EXPECT_TRUE(root.tableArray("list").empty());
  EXPECT_FALSE(root.has("b"));
  EXPECT_NO_THROW(root.finish());
}

TEST(TableReader, KeysInDocumentOrder) {
  const toml::table doc = core::parseTomlString("z = 1\na = 2\nm = 3\n", "x.toml");
  const core::TableReader root(doc, "x.toml");
  auto keys = root.keys();
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(keys, (std::vector<std::string>{"a", "m", "z"}));
}

// --set overrides: nested keys, typed values, tables created on the way.
TEST(ApplyOverride, SetsNestedKeysWithTypedValues) {
  toml::table doc = core::parseTomlString(kCase, "case.toml");
  core::applyOverride(doc, "solver.tolerance=1e-6");
  core::applyOverride(doc, "steps=400");
  core::applyOverride(doc, "title=\"blast roof\"");
  core::applyOverride(doc, "output.name=plain words");
  core::applyOverride(doc, "a.b.c.d=2.5");
  core::applyOverride(doc, "mesh.size=[1, 2, 3]");
  core::applyOverride(doc, "solver.verbose=false");
  EXPECT_EQ(doc["solver"]["tolerance"].value_exact<double>(), 1e-6);
  EXPECT_EQ(doc["steps"].value_exact<std::int64_t>(), 400);
  EXPECT_EQ(doc["title"].value_exact<std::string>(), "blast roof");
  EXPECT_EQ(doc["output"]["name"].value_exact<std::string>(), "plain words");
  EXPECT_EQ(doc["a"]["b"]["c"]["d"].value_exact<double>(), 2.5);
  EXPECT_EQ(doc["mesh"]["size"].as_array()->size(), 3u);
  EXPECT_EQ(doc["solver"]["verbose"].value_exact<bool>(), false);
  // Other keys are untouched.
  EXPECT_EQ(doc["solver"]["max_iterations"].value_exact<std::int64_t>(), 50);
}

// An error about a value a --set gave names the --set, not the file (the
// file's own values keep their file and line): a bad override is not the
// case file's fault.
TEST(ApplyOverride, ErrorsAboutOverriddenValuesNameTheSet) {
  const auto errorOf = [](const char* text, const std::string& assignment, auto read) {
    toml::table doc = core::parseTomlString(text, "case.toml");
    core::applyOverride(doc, assignment);
    const core::TableReader root(doc, "case.toml");
    try {
      read(root);
    } catch (const lamina::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(errorOf(kCase, "steps=abc",
                    [](const core::TableReader& r) { (void)r.getInt("steps"); }),
            "--set steps=abc: 'steps': expected an integer, got string");
  EXPECT_EQ(errorOf(kCase, "solver.tolerance=[1]",
                    [](const core::TableReader& r) {
                      (void)r.table("solver").getDouble("tolerance");
                    }),
            "--set solver.tolerance=[1]: 'solver.tolerance': expected a number, got array");
  // a key the format does not have, in a table the override made
  EXPECT_EQ(errorOf("a = 1\n", "extra.key=1",
                    [](const core::TableReader& r) {
                      (void)r.getInt("a");
                      r.finish();
                    }),
            "--set extra.key=1: 'extra': unknown key (not part of this file's format)");
  // the file's own values still name the file and the line
  EXPECT_EQ(errorOf(kCase, "steps=3", [](const core::TableReader& r) { (void)r.getInt("title"); }),
            "case.toml:1: 'title': expected an integer, got string");
}

TEST(ApplyOverride, RejectsMalformedAssignments) {
  toml::table doc = core::parseTomlString(kCase, "case.toml");
  EXPECT_THROW(core::applyOverride(doc, "novalue"), lamina::Error);
  EXPECT_THROW(core::applyOverride(doc, "=3"), lamina::Error);
  EXPECT_THROW(core::applyOverride(doc, "a..b=3"), lamina::Error);
  // "steps" is a number: it cannot hold a sub-key.
  try {
    core::applyOverride(doc, "steps.x=1");
    FAIL() << "no error";
  } catch (const lamina::Error& e) {
    EXPECT_NE(std::string(e.what()).find("steps.x"), std::string::npos) << e.what();
  }
}
