/// @file malformed_library_test.cpp
/// @brief The library under hostile use (names, concurrent writers, kill -9): names that would escape
/// the library's folder or inject card lines, side files in the entry's
/// transaction (races, failures, kill -9), stale temporaries, a library that
/// is a symlink, a side_file path pointing outside.

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "materials/export.hpp"
#include "materials/library.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <set>

namespace fs = std::filesystem;
namespace mat = lamina::materials;
using lamina::test::errorOf;
using lamina::test::readFile;
using lamina::test::TempDir;
using lamina::test::writeFile;

namespace {

mat::Material iso(const std::string& name, double density) {
  mat::Material m;
  m.name = name;
  m.C = mat::Stiffness::isotropic(1e9, 0.3);
  m.density = density;
  m.kind = "constants";
  return m;
}

/// A side writer that puts @p text into the .h5 path it is given and a
/// companion .xdmf beside it (as the phase map writer does).
mat::Library::SideFileWriter sideText(const std::string& text) {
  return [text](const fs::path& h5) {
    writeFile(h5, text);
    fs::path x = h5;
    writeFile(x.replace_extension(".xdmf"), "xdmf of " + text);
  };
}

/// @return the files of @p dir (recursively) that no entry of the library at
/// @p lib names and that are not the library or its lock: the orphans and
/// temporaries the issue found after kill -9.
std::vector<std::string> debris(const fs::path& dir, const fs::path& lib) {
  const mat::Library l(lib);
  std::set<std::string> named{lib.filename().string(), lib.filename().string() + ".lock"};
  for (const auto& n : l.names())
    if (!l.get(n).side_file.empty()) {
      fs::path s = l.get(n).side_file;
      named.insert(s.string());
      named.insert(s.replace_extension(".xdmf").string());
    }
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (!e.is_directory()) {
      const std::string rel = fs::relative(e.path(), dir).string();
      if (!named.count(rel))
        out.push_back(rel);
    }
  return out;
}

} // namespace

// `--name ../../x`, an absolute name or a newline never reach the file
// system or the file: add refuses them and writes nothing.
TEST(LibraryNames, PathAndControlNamesAreRefused) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  mat::Library lib(path);
  const std::vector<std::string> names{"../../x",   "/tmp/x",
                                       "a/b",       "evil\n*INCLUDE, INPUT=/etc/passwd",
                                       ".hidden",   std::string("nul\0x", 5),
                                       "with space"};
  for (const std::string& bad : names) {
    const std::string msg = errorOf([&] { lib.add(iso(bad, 1000), false, sideText("x")); });
    EXPECT_NE(msg.find("material name"), std::string::npos) << bad << ": " << msg;
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(debris(dir.path(), path).empty());
}

// A library file holding a bad name (hand-edited) is refused naming the
// file and the entry's line; so is a side_file that leaves the folder.
TEST(LibraryNames, BadNamesAndSidePathsInTheFileNameFileAndLine) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  const std::string head = "[lamina]\nformat = \"lamina-materials-library\"\nversion = 1\n";
  const std::string body = "kind = \"constants\"\ndensity = 1000.0\nC = [[1e9,0,0,0,0,0],"
                           "[0,1e9,0,0,0,0],[0,0,1e9,0,0,0],[0,0,0,1e9,0,0],[0,0,0,0,1e9,0],"
                           "[0,0,0,0,0,1e9]]\n";
  writeFile(path, head + "[materials.\"a\\nb\"]\n" + body); // line 4
  std::string msg = errorOf([&] { mat::Library{path}; });
  EXPECT_NE(msg.find(path.string() + ":4"), std::string::npos) << msg;
  writeFile(path, head + "[materials.ok]\n" + body + "side_file = \"../../etc/passwd\"\n");
  msg = errorOf([&] { mat::Library{path}; });
  EXPECT_NE(msg.find("side_file"), std::string::npos) << msg;
}

// Card exports refuse a name that would start a line of its own.
TEST(LibraryNames, ExportRefusesNewlinesInNames) {
  for (const auto& [name, format] : mat::kExportFormatNames) {
    const std::string msg =
        errorOf([&] { mat::exportCard(iso("x\n*INCLUDE, INPUT=evil.inp", 1000), format); });
    EXPECT_NE(msg.find("material name"), std::string::npos) << name << ": " << msg;
  }
}

// The side file lands with its entry, in the library's side folder; a
// failing writer or a failing add leaves neither, and an overwrite that
// fails puts the previous side file back.
TEST(LibrarySideFiles, SideFileIsPartOfTheTransaction) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  mat::Library lib(path);
  lib.add(iso("a", 1000), false, sideText("first"));
  const std::string first = lib.get("a").side_file;
  ASSERT_EQ(first.rfind("lib.side/a.", 0), 0u) << first;
  EXPECT_EQ(readFile(dir / first), "first");
  const std::string before = readFile(path);

  auto throwing = [](const fs::path& h5) {
    writeFile(h5, "half");
    throw lamina::Error("disk full (simulated)");
  };
  EXPECT_THROW(lib.add(iso("b", 1000), false, throwing), lamina::Error);
  EXPECT_THROW(lib.add(iso("a", 1000), true, throwing), lamina::Error);
  // An entry that fails its read-back check (provenance nested past the
  // TOML depth limit) after the side file was placed.
  mat::Material bad = iso("a", 1000);
  toml::table deep{{"x", 1}};
  for (int i = 0; i < 80; ++i)
    deep = toml::table{{"n", deep}};
  bad.provenance.insert("deep", deep);
  EXPECT_THROW(lib.add(bad, true, sideText("second")), std::exception);
  EXPECT_EQ(readFile(path), before);
  EXPECT_EQ(readFile(dir / first), "first");
  EXPECT_TRUE(debris(dir.path(), path).empty()) << debris(dir.path(), path).front();

  lib.add(iso("a", 2000), true, sideText("second"));
  const std::string second = mat::Library(path).get("a").side_file;
  EXPECT_EQ(readFile(dir / second), "second");
  fs::path x = dir / second;
  EXPECT_EQ(readFile(x.replace_extension(".xdmf")), "xdmf of second");
  EXPECT_FALSE(fs::exists(dir / first)); // the replaced entry's file went with it
  lib.remove("a");
  EXPECT_TRUE(debris(dir.path(), path).empty()) << debris(dir.path(), path).front();
}

// What a killed writer leaves (library temporaries, stage folders, side
// files no entry names) is removed by the next write, under the lock.
TEST(LibrarySideFiles, StaleTemporariesAreCleanedByTheNextWrite) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  mat::Library(path).add(iso("keep", 1000), false, sideText("k"));
  const std::string keep = mat::Library(path).get("keep").side_file;
  writeFile(dir / "lib.toml.tmp.AbC123", "torn");
  fs::create_directories(dir / "lib.side/.stage.XyZ789/replaced");
  writeFile(dir / "lib.side/.stage.XyZ789/ghost.h5", "x");
  writeFile(dir / "lib.side/orphan.h5", "x");
  writeFile(dir / "other.toml.tmp.AbC123", "not ours"); // another library's: kept
  mat::Library(path).add(iso("next", 1000));
  EXPECT_EQ(debris(dir.path(), path), std::vector<std::string>{"other.toml.tmp.AbC123"});
  EXPECT_EQ(readFile(dir / keep), "k");
}

// A library reached through a symlink stays a symlink (the real file gets
// the entry, the side folder sits beside the real file) and keeps its
// permissions.
TEST(LibrarySideFiles, SymlinkedLibraryStaysALinkWithItsPermissions) {
  TempDir dir;
  fs::create_directories(dir / "real");
  const auto real = dir / "real/lib.toml";
  mat::Library(real).add(iso("a", 1000));
  ASSERT_EQ(::chmod(real.c_str(), 0640), 0);
  const auto link = dir / "link.toml";
  fs::create_symlink(real, link);
  mat::Library(link).add(iso("b", 1000), false, sideText("b"));
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_TRUE(mat::Library(real).contains("b"));
  const std::string side = mat::Library(link).get("b").side_file;
  EXPECT_EQ(side.rfind("lib.side/", 0), 0u) << side;
  EXPECT_EQ(readFile(dir / "real" / side), "b");
  struct stat st {};
  ASSERT_EQ(::stat(real.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
}

// Two processes add the same name with --overwrite, 10 times each, each with
// a side file holding its own density: whoever wins, the side file always
// belongs to the entry the library holds (the issue: 16 of 20 races gave the
// other cell's side file or none).
TEST(LibrarySideFiles, ConcurrentWritersOfOneNameKeepEntryAndSideFileTogether) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  std::vector<pid_t> kids;
  for (int who = 1; who <= 2; ++who)
    kids.push_back(lamina::test::forkChild([&path, who] {
      for (int k = 0; k < 10; ++k) {
        const double density = 1000.0 * who + k;
        mat::Library(path).add(iso("x", density), true, sideText(std::to_string(density)));
      }
    }));
  lamina::test::expectChildrenSucceed(kids);
  const mat::Library lib(path);
  EXPECT_EQ(readFile(dir / lib.get("x").side_file), std::to_string(lib.get("x").density));
  EXPECT_TRUE(debris(dir.path(), path).empty());
}

// A writer of entries with side files killed (SIGKILL) at arbitrary
// moments: the library stays readable, every entry's side file exists and
// matches it, and after the next add nothing else is left in the folder.
TEST(LibrarySideFiles, KilledWriterLeavesNoOrphans) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  for (int round = 0; round < 4; ++round) {
    const pid_t pid = lamina::test::forkChild([&path] {
      for (int k = 0; k < 100000; ++k)
        mat::Library(path).add(iso("e" + std::to_string(k % 7), 1000 + k), true,
                               sideText(std::to_string(1000.0 + k)));
    });
    ::usleep(static_cast<useconds_t>(20000 + 13000 * round));
    ::kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    const mat::Library lib(path);     // never torn
    for (const auto& n : lib.names()) // the side file is the entry's own
      EXPECT_EQ(readFile(dir / lib.get(n).side_file), std::to_string(lib.get(n).density)) << n;
  }
  mat::Library(path).add(iso("after", 1000), false, sideText("after"));
  EXPECT_TRUE(debris(dir.path(), path).empty()) << debris(dir.path(), path).front();
}

// A command that adds several entries (a J sweep, --tangent-rates) adds all
// or none: names that repeat among them, a name already in the library, an
// invalid entry or a side writer failing after the first entry's side file
// was placed all leave the library byte for byte as it was and no side file.
TEST(LibraryTransactions, SeveralEntriesAreAddedAllOrNone) {
  TempDir dir;
  const auto path = dir / "lib.toml";
  mat::Library(path).add(iso("old", 1000), false, sideText("old"));
  const std::string before = readFile(path);
  auto two = [](const std::string& a, const std::string& b, mat::Library::SideFileWriter second) {
    std::vector<mat::Library::Addition> v;
    v.push_back({iso(a, 1000), sideText(a)});
    v.push_back({iso(b, 2000), std::move(second)});
    return v;
  };
  mat::Library lib(path);
  std::string msg = errorOf([&] { lib.add(two("p-R1e+05", "p-R1e+05", sideText("b")), false); });
  EXPECT_NE(msg.find("two of the entries to add are named 'p-R1e+05'"), std::string::npos) << msg;
  msg = errorOf([&] { lib.add(two("new", "old", sideText("b")), false); });
  EXPECT_NE(msg.find("'old' is already in library"), std::string::npos) << msg;
  auto failing = [](const fs::path& h5) {
    writeFile(h5, "partial");
    throw lamina::Error("disk full (test)");
  };
  EXPECT_THROW(lib.add(two("x1", "x2", failing), false), lamina::Error);
  std::vector<mat::Library::Addition> bad = two("y1", "y2", sideText("y2"));
  bad[1].material.density = -1; // invalid: refused before anything is written
  EXPECT_THROW(lib.add(bad, false), lamina::Error);
  EXPECT_EQ(readFile(path), before);
  EXPECT_EQ(mat::Library(path).names(), (std::vector<std::string>{"old"}));
  EXPECT_TRUE(debris(dir.path(), path).empty());
  // and the good pair lands whole, each entry with its own side file
  lib.add(two("z1", "z2", sideText("z2")), false);
  const mat::Library after(path);
  EXPECT_EQ(after.names(), (std::vector<std::string>{"old", "z1", "z2"}));
  EXPECT_EQ(readFile(dir / after.get("z1").side_file), "z1");
  EXPECT_EQ(readFile(dir / after.get("z2").side_file), "z2");
}

// Side files take the library's permission bits, and the side folder is no
// more open than the library (x where r is set): a 0600 library gets 0600
// side files in a 0700 folder, a 0640 one 0640 files in a 0750 folder (the
// issue: 0644 side files under a 0600 library).
TEST(LibrarySideFiles, SideFilesTakeTheLibrarysMode) {
  for (const auto& [lib_mode, folder_mode] :
       std::vector<std::pair<mode_t, mode_t>>{{0600, 0700}, {0640, 0750}, {0444, 0755}}) {
    TempDir dir;
    const auto path = dir / "lib.toml";
    mat::Library(path).add(iso("a", 1000));
    ASSERT_EQ(::chmod(path.c_str(), lib_mode), 0);
    mat::Library(path).add(iso("b", 1000), false, sideText("b"));
    const fs::path h5 = dir / mat::Library(path).get("b").side_file;
    fs::path xdmf = h5;
    xdmf.replace_extension(".xdmf");
    struct stat st {};
    for (const fs::path& f : {h5, xdmf}) {
      ASSERT_EQ(::stat(f.c_str(), &st), 0) << f;
      EXPECT_EQ(st.st_mode & 07777, lib_mode) << f;
    }
    ASSERT_EQ(::stat((dir / "lib.side").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, folder_mode);
    ASSERT_EQ(::stat(path.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, lib_mode); // and the library keeps its own
  }
}
