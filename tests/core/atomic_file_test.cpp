// writeFileAtomically replaces content (write aside, rename) and leaves no
// temporary behind; a failed replacement keeps the target; FileLock excludes
// other lockers of the same file until it is released.

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "test_util.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace core = lamina::core;
namespace fs = std::filesystem;

namespace {

int entries(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
    ++n;
  return n;
}

} // namespace

TEST(AtomicFile, WritesThenReplacesContent) {
  const lamina::test::TempDir d;
  const fs::path p = d.path() / "sub" / "out.txt";
  core::writeFileAtomically(p, "first\n");
  EXPECT_EQ(lamina::test::readFile(p), "first\n");
  std::string big(1 << 20, 'x'); // 1 MiB: several write() calls
  big[12345] = '\0';
  core::writeFileAtomically(p, big);
  EXPECT_EQ(lamina::test::readFile(p), big);
  core::writeFileAtomically(p, "");
  EXPECT_EQ(lamina::test::readFile(p), "");
  EXPECT_EQ(entries(d.path() / "sub"), 1); // no temporary left beside it
  EXPECT_EQ(fs::status(p).permissions() & fs::perms::owner_read, fs::perms::owner_read);
}

// Replacing a directory fails: the error names the target, the directory is
// untouched and the temporary is removed.
TEST(AtomicFile, FailedRenameKeepsTargetAndCleansUp) {
  const lamina::test::TempDir d;
  const fs::path target = d.path() / "occupied";
  fs::create_directories(target / "inside");
  try {
    core::writeFileAtomically(target, "data");
    FAIL() << "no error";
  } catch (const lamina::Error& e) {
    EXPECT_EQ(e.context().file, target.string()) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(target / "inside"));
  EXPECT_EQ(entries(d.path()), 1);
}

TEST(AtomicFile, RenameIntoPlaceMovesFile) {
  const lamina::test::TempDir d;
  core::writeFileAtomically(d.path() / "a.tmp", "payload");
  core::writeFileAtomically(d.path() / "a", "old");
  core::renameIntoPlace(d.path() / "a.tmp", d.path() / "a");
  EXPECT_EQ(lamina::test::readFile(d.path() / "a"), "payload");
  EXPECT_FALSE(fs::exists(d.path() / "a.tmp"));
}

// flock locks belong to open file descriptions: a second descriptor cannot
// take the lock while the FileLock lives, and can once it is gone.
TEST(FileLock, ExcludesOtherLockersUntilReleased) {
  const lamina::test::TempDir d;
  const fs::path lib = d.path() / "library.toml";
  auto tryLock = [&] {
    const int fd = ::open((lib.string() + ".lock").c_str(), O_RDWR);
    EXPECT_GE(fd, 0);
    const bool got = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    ::close(fd);
    return got;
  };
  {
    const core::FileLock lock(lib);
    EXPECT_TRUE(fs::exists(lib.string() + ".lock"));
    EXPECT_FALSE(tryLock());
  }
  EXPECT_TRUE(tryLock());
}

// An output replaces only a regular file: a FIFO, a symlink to a character
// device (/dev/null) and a directory are refused, named in the error, and
// are still what they were afterwards; nothing is left beside them.
TEST(AtomicFile, RefusesToReplaceWhatIsNotARegularFile) {
  const lamina::test::TempDir d;
  const fs::path fifo = d.path() / "fifo.csv", null_link = d.path() / "null.csv",
                 folder = d.path() / "folder.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  fs::create_symlink("/dev/null", null_link);
  fs::create_directories(folder);
  for (const fs::path& p : {fifo, null_link, folder}) {
    const std::string msg = lamina::test::errorOf([&] { core::writeFileAtomically(p, "x"); });
    EXPECT_NE(msg.find("refusing to write over"), std::string::npos) << p << ": " << msg;
    EXPECT_NE(msg.find(p.filename().string() == "null.csv" ? "/dev/null" : p.string()),
              std::string::npos)
        << msg;
    EXPECT_THROW(core::checkReplaceable(p, "--out"), lamina::Error);
    core::writeFileAtomically(d.path() / "aside", "payload");
    EXPECT_THROW(core::renameIntoPlace(d.path() / "aside", p), lamina::Error);
    EXPECT_FALSE(fs::exists(d.path() / "aside")); // the temporary is removed
  }
  struct stat st {};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_TRUE(fs::is_symlink(null_link));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_TRUE(fs::is_directory(folder));
  EXPECT_EQ(entries(d.path()), 3);
  core::checkReplaceable(d.path() / "new.csv", "--out"); // absent: fine
}

// An output that is an input of the run (the same file by another name: a
// symlink, a hard link, a path with "..") is refused naming both.
TEST(AtomicFile, RefusesAnOutputThatIsAnInput) {
  const lamina::test::TempDir d;
  const fs::path lib = d.path() / "lib.toml";
  lamina::test::writeFile(lib, "library");
  fs::create_directories(d.path() / "sub");
  fs::create_symlink(lib, d.path() / "link.toml");
  fs::create_hard_link(lib, d.path() / "hard.toml");
  for (const fs::path& out :
       {lib, d.path() / "link.toml", d.path() / "hard.toml", d.path() / "sub/../lib.toml"}) {
    const std::string msg = lamina::test::errorOf([&] {
      core::checkOutput(out, {d.path() / "cell.toml", lib}, "--out");
    });
    EXPECT_NE(msg.find("is an input of the run (" + lib.string() + ")"), std::string::npos)
        << out << ": " << msg;
    EXPECT_NE(msg.find("--out"), std::string::npos) << msg;
  }
  core::checkOutput(d.path() / "other.csv", {lib, ""}, "--out"); // a new file: fine
  EXPECT_EQ(lamina::test::readFile(lib), "library");
}
