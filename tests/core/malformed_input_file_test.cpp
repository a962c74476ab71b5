/// @file malformed_input_file_test.cpp
/// @brief Inputs that are not regular files, through the one gate of
/// core/input_file.hpp and the core readers built on it (TOML, HDF5): a FIFO
/// with no writer (blocked open() forever), a directory, a socket, a symlink
/// to /dev/null and a symlink to the FIFO are each refused promptly with an
/// error naming the file and what it is; a symlink to a regular file is
/// read; a file above its reader's bound is refused from its size.

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "core/toml_reader.hpp"
#include "test_util.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

namespace core = lamina::core;
using lamina::test::errorOf;
using lamina::test::HangGuard;
using lamina::test::notRegularFiles;
using lamina::test::TempDir;

namespace {

/// The words naming what each of notRegularFiles() is, in its order.
const char* const kKinds[] = {"FIFO", "directory", "socket", "character device", "FIFO"};

} // namespace

// Every kind of non-file through every entry of the gate and the TOML and
// HDF5 readers: an error naming the path and the kind. The guard fails the
// test if any of them blocks (a FIFO without a writer blocks a plain open).
TEST(NotRegularFiles, RefusedPromptlyNamingFileAndKind) {
  const HangGuard guard(20);
  TempDir dir;
  const auto paths = notRegularFiles(dir, ".toml");
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const auto& p = paths[i];
    for (const auto& read : std::vector<std::function<void()>>{
             [&] { core::checkRegularInput(p, "pressure table", core::kMaxTableBytes); },
             [&] { core::readWholeFile(p, core::kMaxTableBytes, "pressure table"); },
             [&] { core::parseTomlFile(p); },
             [&] { core::H5File(p, core::H5File::Mode::ReadOnly); },
             [&] { core::H5File(p, core::H5File::Mode::ReadWrite); }}) {
      const std::string msg = errorOf(read);
      EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
      EXPECT_NE(msg.find(kKinds[i]), std::string::npos) << msg;
      EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
    }
  }
}

// A symlink to a regular file is an ordinary input: read through it, with
// the size of its target.
TEST(NotRegularFiles, SymlinkToRegularFileIsRead) {
  TempDir dir;
  lamina::test::writeFile(dir / "t.csv", "0,1\n1,2\n");
  std::filesystem::create_symlink(dir / "t.csv", dir / "link.csv");
  EXPECT_EQ(core::checkRegularInput(dir / "link.csv", "pressure table", 100), 8u);
  EXPECT_EQ(core::readWholeFile(dir / "link.csv", 100, "pressure table"), "0,1\n1,2\n");
}

// The bound of a reader is checked from the size, before reading: 9 bytes
// against a bound of 8 is refused naming both numbers; 8 against 8 is read.
TEST(NotRegularFiles, SizeBoundRefusesBeforeReading) {
  TempDir dir;
  lamina::test::writeFile(dir / "t.csv", "0,1\n1,2\n\n");
  const std::string msg =
      errorOf([&] { core::readWholeFile(dir / "t.csv", 8, "pressure table"); });
  EXPECT_NE(msg.find((dir / "t.csv").string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("9 bytes exceeds the limit of 8 bytes for a pressure table"),
            std::string::npos)
      << msg;
  EXPECT_EQ(core::readWholeFile(dir / "t.csv", 9, "pressure table").size(), 9u);
}

// A missing file names the file and the system's reason; readAt past the
// end says the file ends before what its header describes.
TEST(NotRegularFiles, MissingFileAndShortReadNameTheFile) {
  TempDir dir;
  std::string msg = errorOf([&] { core::readWholeFile(dir / "none.csv", 8, "pressure table"); });
  EXPECT_NE(msg.find("none.csv"), std::string::npos) << msg;
  EXPECT_NE(msg.find("No such file"), std::string::npos) << msg;
  lamina::test::writeFile(dir / "s.raw", "abcd");
  const core::InputFile in(dir / "s.raw", "image", 100, {"cell.toml", 0, "cell.image"});
  char buf[8];
  msg = errorOf([&] { in.readAt(2, buf, 4); });
  EXPECT_NE(msg.find("cell.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("s.raw"), std::string::npos) << msg;
  EXPECT_NE(msg.find("ends at byte 4"), std::string::npos) << msg;
}
