// The strict TOML reader on bad input: every error is a lamina::Error whose
// one-line message names the file, the line and the dotted key.

#include "core/error.hpp"
#include "core/toml_reader.hpp"

#include <gtest/gtest.h>

#include <functional>

namespace core = lamina::core;

namespace {

lamina::Error errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const lamina::Error& e) {
    return e;
  }
  ADD_FAILURE() << "no lamina::Error thrown";
  return lamina::Error("none");
}

const char* kCase = "title = \"x\"\n"    // 1
                    "[solver]\n"         // 2
                    "tolerance = 1e-8\n" // 3
                    "tolerence = 1e-6\n" // 4: the typo
                    "[[loads]]\n"        // 5
                    "kind = \"point\"\n" // 6
                    "[[loads]]\n"        // 7
                    "kind = \"drag\"\n"  // 8
                    "magnitde = 3.0\n";  // 9: another typo

} // namespace

// The first unread key is reported with file, its line and its dotted path.
TEST(TomlErrors, UnknownKeyNamesFileLineAndDottedKey) {
  const toml::table doc = core::parseTomlString(kCase, "case.toml");
  const core::TableReader root(doc, "case.toml");
  root.getString("title");
  root.table("solver").getDouble("tolerance");
  for (const auto& l : root.tableArray("loads")) {
    l.getString("kind");
    l.getDouble("magnitde", 0.0); // optional read: marks the second typo as known
  }
  const lamina::Error e = errorOf([&] { root.finish(); });
  EXPECT_EQ(e.context().file, "case.toml");
  EXPECT_EQ(e.context().line, 4);
  EXPECT_EQ(e.context().key, "solver.tolerence");
  EXPECT_EQ(std::string(e.what()).rfind("case.toml:4: 'solver.tolerence': ", 0), 0u) << e.what();
}

TEST(TomlErrors, UnknownKeyInArrayOfTablesIsIndexed) {
  const toml::table doc = core::parseTomlString(kCase, "case.toml");
  const core::TableReader root(doc, "case.toml");
  root.getString("title");
  const auto solver = root.table("solver");
  solver.getDouble("tolerance");
  solver.getDouble("tolerence");
  for (const auto& l : root.tableArray("loads"))
    l.getString("kind");
  const lamina::Error e = errorOf([&] { root.finish(); });
  EXPECT_EQ(e.context().key, "loads[1].magnitde");
  EXPECT_EQ(e.context().line, 9);
}

TEST(TomlErrors, UnreadTableIsUnknown) {
  const toml::table doc = core::parseTomlString("a = 1\n[extra]\nb = 2\n", "x.toml");
  const core::TableReader root(doc, "x.toml");
  root.getInt("a");
  const lamina::Error e = errorOf([&] { root.finish(); });
  EXPECT_EQ(e.context().key, "extra");
  EXPECT_EQ(e.context().line, 2);
}

TEST(TomlErrors, WrongTypeNamesKeyLineAndBothTypes) {
  const toml::table doc =
      core::parseTomlString("[solver]\nsteps = 2.5\nname = 3\nok = \"yes\"\n", "x.toml");
  const core::TableReader solver = core::TableReader(doc, "x.toml").table("solver");
  lamina::Error e = errorOf([&] { solver.getInt("steps"); });
  EXPECT_EQ(e.context().key, "solver.steps");
  EXPECT_EQ(e.context().line, 2);
  EXPECT_NE(e.message().find("expected an integer, got float"), std::string::npos) << e.what();
  e = errorOf([&] { solver.getString("name"); });
  EXPECT_EQ(e.context().key, "solver.name");
  EXPECT_EQ(e.context().line, 3);
  e = errorOf([&] { solver.getDouble("ok"); });
  EXPECT_NE(e.message().find("expected a number, got string"), std::string::npos) << e.what();
  e = errorOf([&] { solver.getBool("ok", false); });
  EXPECT_EQ(e.context().key, "solver.ok");
  e = errorOf([&] { solver.table("steps"); });
  EXPECT_NE(e.message().find("expected a table"), std::string::npos) << e.what();
  e = errorOf([&] { solver.getDoubleArray("steps"); });
  EXPECT_EQ(e.context().key, "solver.steps");
}

TEST(TomlErrors, BadArrayElementsNameTheKey) {
  const toml::table doc =
      core::parseTomlString("v = [1.0, \"two\"]\nm = [[1, 2], 3]\ns = [\"a\", 1]\n", "x.toml");
  const core::TableReader root(doc, "x.toml");
  EXPECT_EQ(errorOf([&] { root.getDoubleArray("v"); }).context().key, "v");
  EXPECT_EQ(errorOf([&] { root.getMatrix("m"); }).context().key, "m");
  EXPECT_EQ(errorOf([&] { root.getStringArray("s"); }).context().key, "s");
}

TEST(TomlErrors, MissingKeyNamesTheDottedKey) {
  const toml::table doc = core::parseTomlString("[mesh]\nnx = 4\n", "x.toml");
  const core::TableReader mesh = core::TableReader(doc, "x.toml").table("mesh");
  const lamina::Error e = errorOf([&] { mesh.getInt("ny"); });
  EXPECT_EQ(e.context().key, "mesh.ny");
  EXPECT_EQ(e.context().file, "x.toml");
  EXPECT_NE(e.message().find("missing"), std::string::npos) << e.what();
}

// A syntax error names the source and the line of the error.
TEST(TomlErrors, SyntaxErrorNamesFileAndLine) {
  const lamina::Error e =
      errorOf([] { core::parseTomlString("a = 1\nb = 2\nc = [1, 2\nd = 4\n", "broken.toml"); });
  EXPECT_EQ(e.context().file, "broken.toml");
  EXPECT_GE(e.context().line, 3);
  EXPECT_LE(e.context().line, 4);
  EXPECT_EQ(std::string(e.what()).rfind("broken.toml:", 0), 0u) << e.what();
  const lamina::Error dup =
      errorOf([] { core::parseTomlString("a = 1\nb = 2\na = 3\n", "dup.toml"); });
  EXPECT_EQ(dup.context().line, 3);
}

TEST(TomlErrors, MissingFileNamesThePath) {
  const lamina::Error e = errorOf([] { core::parseTomlFile("/nonexistent/dir/case.toml"); });
  EXPECT_EQ(e.context().file, "/nonexistent/dir/case.toml");
}

// Error formatting: "FILE:LINE: 'KEY': MESSAGE", one line, parts only when known.
TEST(TomlErrors, ErrorTextHasOnlyKnownParts) {
  EXPECT_STREQ(lamina::Error("boom", {"f.toml", 3, "a.b"}).what(), "f.toml:3: 'a.b': boom");
  EXPECT_STREQ(lamina::Error("boom", {"f.toml", 0, ""}).what(), "f.toml: boom");
  EXPECT_STREQ(lamina::Error("boom", {"", 0, "steel"}).what(), "'steel': boom");
  EXPECT_STREQ(lamina::Error("boom").what(), "boom");
}

// A choice key maps its names to an enum; another name is an error naming the
// file, line and key and listing every accepted name; an absent key gives the
// fallback.
TEST(TomlErrors, UnknownChoiceNamesKeyAndListsTheChoices) {
  enum class Pick { A, B, C };
  const toml::table doc =
      core::parseTomlString("[loads]\nkind = \"b\"\nshape = \"triangle\"\n", "case.toml");
  const core::TableReader loads = core::TableReader(doc, "case.toml").table("loads");
  const auto choices = {std::pair<std::string_view, Pick>{"a", Pick::A},
                        std::pair<std::string_view, Pick>{"b", Pick::B},
                        std::pair<std::string_view, Pick>{"c", Pick::C}};
  EXPECT_EQ(loads.getChoice("kind", choices, Pick::A), Pick::B);
  EXPECT_EQ(loads.getChoice("absent", choices, Pick::C), Pick::C);
  const lamina::Error e = errorOf([&] { loads.getChoice("shape", choices, Pick::A); });
  EXPECT_EQ(e.context().file, "case.toml");
  EXPECT_EQ(e.context().line, 3);
  EXPECT_EQ(e.context().key, "loads.shape");
  EXPECT_NE(
      std::string(e.what()).find("unknown value \"triangle\" (expected \"a\", \"b\" or \"c\")"),
      std::string::npos)
      << e.what();
}
