/// @file malformed_input_limits_test.cpp
/// @brief Hostile input to the core readers: TOML nested or
/// dotted deep enough to overflow toml++'s recursion, oversized files,
/// non-finite numbers, out-of-range integers, names that would become paths
/// or card lines, text written into XML. Each is refused with an error that
/// names the file, the line or the key; nothing crashes.

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/names.hpp"
#include "core/resources.hpp"
#include "core/toml_reader.hpp"
#include "test_util.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <string>

namespace core = lamina::core;
using lamina::test::errorOf;
using lamina::test::repeat;
using lamina::test::TempDir;

// The reproducer: a key of 50000 dots overflowed the stack inside
// toml++. It is refused before parsing, naming the file and the line.
TEST(TomlLimits, DeepDottedKeyIsRefusedNamingFileAndLine) {
  const std::string text = "x = 1\n" + std::string("a") + repeat(".a", 50000) + " = 1\n";
  const std::string msg = errorOf([&] { core::parseTomlString(text, "d.toml"); });
  EXPECT_NE(msg.find("d.toml:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("nested deeper"), std::string::npos) << msg;
}

// Every way of nesting counts: headers, inline tables, arrays, and a
// dotted key under a deep [table] header adds to the header's depth.
TEST(TomlLimits, EveryKindOfNestingCounts) {
  const int deep = core::kMaxTomlDepth + 1;
  const std::vector<std::string> bad{
      "[" + std::string("t") + repeat(".t", deep) + "]\nx = 1\n",
      "v = " + repeat("[", deep) + repeat("]", deep) + "\n",
      "v = " + repeat("{a = ", deep) + "1" + repeat("}", deep) + "\n",
      "[" + std::string("t") + repeat(".t", 40) + "]\n" + "k" + repeat(".k", 40) + " = 1\n",
  };
  for (const auto& text : bad)
    EXPECT_NE(errorOf([&] { core::parseTomlString(text, "n.toml"); }).find("n.toml:"),
              std::string::npos)
        << text.substr(0, 80);
}

// Dots and brackets inside strings and comments, and floats, are not
// nesting: such files at the limit parse.
TEST(TomlLimits, DotsInStringsCommentsAndNumbersDoNotCount) {
  const std::string many = repeat(".", 500);
  const std::string text = "s = \"" + many + "[[[{{{\"\n" + "l = '" + many + "'\n" +
                           "m = \"\"\"\n" + many + "\n\"\"\"\n" + "# " + many + repeat("[", 200) +
                           "\n" + "f = [1.5, 2.5, 3.5]\n" + "\"quoted.key" + many + "\" = 1\n" +
                           std::string("a") + repeat(".a", core::kMaxTomlDepth - 2) + " = 2\n";
  EXPECT_NO_THROW(core::parseTomlString(text, "ok.toml"));
}

// A --set override is held to the same limit.
TEST(TomlLimits, DeepOverrideIsRefused) {
  toml::table doc;
  const std::string key = std::string("a") + repeat(".a", 5000);
  EXPECT_NE(errorOf([&] { core::applyOverride(doc, key + "=1"); }).find("nested deeper"),
            std::string::npos);
  EXPECT_NE(
      errorOf([&] { core::applyOverride(doc, "v=" + repeat("[", 5000)); }).find("nested deeper"),
      std::string::npos);
}

// A file above the size limit is refused from its size, before reading; a
// folder or a missing file is named as such.
TEST(TomlLimits, OversizedFileAndNonFilesAreRefused) {
  TempDir dir;
  const auto big = dir / "big.toml";
  {
    lamina::test::writeFile(big, "a = 1\n");
    ASSERT_EQ(::truncate(big.c_str(), static_cast<off_t>(core::kMaxTomlBytes + 1)), 0);
  }
  std::string msg = errorOf([&] { core::parseTomlFile(big); });
  EXPECT_NE(msg.find(big.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("exceeds"), std::string::npos) << msg;
  msg = errorOf([&] { core::parseTomlFile(dir.path()); });
  EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
}

// nan and inf are valid TOML but never a valid input number: the key and
// its line are named (was: "Young's modulus must be positive, got inf").
TEST(TomlLimits, NonFiniteNumbersNameTheKey) {
  const toml::table doc =
      core::parseTomlString("E = inf\nv = [1.0, nan]\nm = [[1.0], [-inf]]\n", "x.toml");
  const core::TableReader r(doc, "x.toml");
  EXPECT_NE(errorOf([&] { r.getDouble("E"); }).find("x.toml:1: 'E'"), std::string::npos)
      << errorOf([&] { r.getDouble("E"); });
  EXPECT_NE(errorOf([&] { r.getDoubleArray("v"); }).find("'v'"), std::string::npos);
  EXPECT_NE(errorOf([&] { r.getMatrix("m"); }).find("finite"), std::string::npos);
}

// Integers are range-checked before any narrowing: 4294967304 = 2^32 + 8
// became 8 through a cast to int.
TEST(TomlLimits, IntegersOutOfRangeAreRefusedNotWrapped) {
  const toml::table doc = core::parseTomlString("n = 4294967304\nk = 8\n", "x.toml");
  const core::TableReader r(doc, "x.toml");
  const std::string msg = errorOf([&] { r.getIntIn("n", 2, 4096); });
  EXPECT_NE(msg.find("4294967304"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[2, 4096]"), std::string::npos) << msg;
  EXPECT_EQ(r.getIntIn("k", 2, 4096), 8);
  EXPECT_EQ(r.getIntIn("absent", 2, 4096, 32), 32);
}

// The name rule of core/names.hpp: what may become a file name, a CSV
// column and a card line.
TEST(Names, RuleAcceptsOrdinaryNamesAndRefusesPathsAndControls) {
  for (const char* ok : {"polyurea-45", "pu-J0.95", "t1-0-90", "CFRP_T300+epoxy", "a", "9"})
    EXPECT_TRUE(core::isValidName(ok)) << ok;
  for (const std::string& bad :
       {std::string(""), std::string("../../x"), std::string("/abs"), std::string(".hidden"),
        std::string("-opt"), std::string("a/b"), std::string("a b"), std::string("a\"b"),
        std::string("a\nb"), std::string("a\rb"), std::string("x\x01"), std::string("a,b"),
        std::string(".."), std::string(core::kMaxNameLength + 1, 'a')})
    EXPECT_FALSE(core::isValidName(bad)) << bad;
  // The message shows a control character as '?', never raw.
  const std::string msg = errorOf([] { core::checkName("evil\n*INCLUDE", "entry name"); });
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_NE(msg.find("byte 0x0a"), std::string::npos) << msg;
}

TEST(Names, XmlEscapeLeavesNoMarkup) {
  EXPECT_EQ(core::xmlEscape("a\"<b>&'c"), "a&quot;&lt;b&gt;&amp;&apos;c");
  EXPECT_EQ(core::xmlEscape("plain.h5"), "plain.h5");
}

// Work whose memory is known is refused up front with the amount; threads
// beyond the machine are refused naming the option.
TEST(Resources, OversizedWorkAndThreadsAreRefusedWithTheAmount) {
  ASSERT_GT(core::availableMemoryBytes(), 0.0) << "/proc/meminfo unreadable";
  const std::string msg = errorOf([] { core::requireMemory(1e30, "a test", {"f.toml", 3, "n"}); });
  EXPECT_NE(msg.find("f.toml:3: 'n'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("needs about"), std::string::npos) << msg;
  EXPECT_NO_THROW(core::requireMemory(1024.0, "a test"));
  EXPECT_NE(errorOf([] { core::checkThreads(100000, "--threads"); }).find("--threads"),
            std::string::npos);
  EXPECT_NO_THROW(core::checkThreads(0, "--threads"));
  EXPECT_NO_THROW(core::checkThreads(core::hardwareThreads(), "--threads"));
  EXPECT_EQ(core::formatBytes(1536.0), "1.5 KiB");
}

// A symlinked file stays a symlink and the file keeps its permissions;
// both names of the file share one lock.
TEST(AtomicFile, SymlinkStaysALinkAndPermissionsAreKept) {
  TempDir dir;
  const auto real = dir / "real.toml";
  const auto link = dir / "link.toml";
  lamina::test::writeFile(real, "old\n");
  ASSERT_EQ(::chmod(real.c_str(), 0600), 0);
  std::filesystem::create_symlink("real.toml", link);
  core::writeFileAtomically(link, "new\n");
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(lamina::test::readFile(real), "new\n");
  struct stat st {};
  ASSERT_EQ(::stat(real.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(core::resolveLinks(link), core::resolveLinks(real));
  // A dangling link: the file it names is created, the link kept.
  const auto dangling = dir / "dangling.toml";
  std::filesystem::create_symlink("later.toml", dangling);
  core::writeFileAtomically(dangling, "x\n");
  EXPECT_TRUE(std::filesystem::is_symlink(dangling));
  EXPECT_EQ(lamina::test::readFile(dir / "later.toml"), "x\n");
}
