/// @file malformed_not_files_test.cpp
/// @brief Inputs that are not regular files, through the programs as a user
/// gives them: a FIFO with no writer (a blast pressure table in a FIFO
/// blocked `membrane run` forever, deaf to SIGINT and SIGTERM), a directory,
/// a socket, a symlink to /dev/null and a symlink to the FIFO, given as a
/// case file, a blast table, a mesh, a cell file, an image and a library.
/// Each: exit 1 within the `timeout` (a hang exits 124), the path and what
/// it is named. Expected substrings are the test's own paths and the kinds
/// of file (FIFO, directory, socket, character device), not the messages.

#include "../core/test_util.hpp"
#include "program.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

using namespace lamina::test;

namespace {

/// The words naming what each of notRegularFiles() is, in its order.
const char* const kKinds[] = {"FIFO", "directory", "socket", "character device", "FIFO"};

/// A fresh folder per test.
class NotFiles : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = std::make_unique<TempDir>();
  }
  /// @return the program's path, behind a 20 s timeout (exit 124 on a hang)
  static std::string bin(const std::string& program) {
    return "timeout -s KILL 20 " + (kBin / program).string();
  }
  /// Runs @p command and expects exit 1 naming @p path as a file of @p kind.
  static void expectRefused(const std::string& command, const fs::path& path, const char* kind) {
    const Result r = run(command);
    EXPECT_EQ(r.code, 1) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(path.string()), std::string::npos) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(kind), std::string::npos) << command << "\n" << r.output;
  }
  /// A small large-deflection case whose tail is @p tail (a blast, a mesh).
  static std::string membraneCase(const std::string& mesh, const std::string& tail) {
    return "name = \"t\"\nmodel = \"large_deflection\"\n" + mesh +
           "[[section]]\nE = 1.0e5\nnu = 0.3\ndensity = 1000.0\nthickness = 1.0e-3\n"
           "prestress = 0.1\n[time]\nt_end = 0.01\n[[fixed]]\nnodes = \"edges\"\n" +
           tail;
  }
  std::unique_ptr<TempDir> dir_;
};

const std::string kRectangle = "[mesh]\ntype = \"rectangle\"\nLx = 1.0\nnx = 2\n";

} // namespace

// The reproducer: a [[blast]] table that is a FIFO. And the case
// file itself, and a gmsh mesh (.msh and .geo), each kind of non-file.
TEST_F(NotFiles, MembraneRefusesCaseTableAndMesh) {
  const TempDir& d = *dir_;
  const auto out = (d / "out").string();
  for (const std::string suffix : {".csv", ".toml", ".msh", ".geo"}) {
    const auto paths = notRegularFiles(d, suffix);
    // meshes: the FIFO and the symlink to /dev/null (each run starts gmsh)
    for (std::size_t i = 0; i < paths.size(); i += suffix == ".msh" || suffix == ".geo" ? 3 : 1) {
      const fs::path& p = paths[i];
      std::string case_file = p.string();
      if (suffix == ".csv") {
        case_file = (d / "blast.toml").string();
        write(case_file, membraneCase(kRectangle, "[[blast]]\ntable = \"" +
                                                      p.filename().string() + "\"\n"));
      } else if (suffix != ".toml") {
        case_file = (d / "mesh.toml").string();
        write(case_file, membraneCase("[mesh]\ntype = \"gmsh\"\nfile = \"" +
                                          p.filename().string() + "\"\n",
                                      ""));
      }
      expectRefused(bin("membrane") + " run '" + case_file + "' --out '" + out + "'", p,
                    kKinds[i]);
    }
    for (const auto& p : paths)
      fs::remove_all(p);
  }
  EXPECT_FALSE(fs::exists(d / "out"));
}

// micro and homogenize: the cell file and the image it names; homogenize and
// materials: the library.
TEST_F(NotFiles, MicroHomogenizeMaterialsRefuseCellImageAndLibrary) {
  const TempDir& d = *dir_;
  const std::string sphere = (kCases / "cells/sphere.toml").string();
  for (const std::string suffix : {".toml", ".tif"}) {
    const auto paths = notRegularFiles(d, suffix);
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const fs::path& p = paths[i];
      std::string cell = p.string();
      if (suffix == ".tif") {
        cell = (d / "image-cell.toml").string();
        write(cell, "[cell]\nimage = \"" + p.filename().string() +
                        "\"\n[[phases]]\nname = \"m\"\nid = 0\nlaw = \"isotropic\"\n"
                        "E = 1e9\nnu = 0.3\ndensity = 1000\n");
      }
      expectRefused(bin("micro") + " '" + cell + "' --out '" + (d / "x.h5").string() + "'", p,
                    kKinds[i]);
      expectRefused(bin("homogenize") + " '" + cell + "' --resolution 8 --quiet", p, kKinds[i]);
      if (suffix == ".toml") {
        expectRefused(bin("materials") + " --library '" + p.string() + "' list", p, kKinds[i]);
        expectRefused(bin("homogenize") + " '" + sphere + "' --resolution 8 --quiet --name s " +
                          "--library '" + p.string() + "'",
                      p, kKinds[i]);
      }
    }
    for (const auto& p : paths)
      fs::remove_all(p);
  }
  EXPECT_FALSE(fs::exists(d / "x.h5"));
}

// Outputs too: a FIFO standing in the output folder where a run writes a
// table (probes.csv.part) or its fields (t.h5) blocked the run in its open;
// each is now refused by name before it is opened, and stays a FIFO.
TEST_F(NotFiles, MembraneRefusesAFifoWhereItWritesAnOutput) {
  const TempDir& d = *dir_;
  const auto case_file = (d / "t.toml").string();
  write(case_file, membraneCase(kRectangle, ""));
  for (const std::string name : {"probes.csv.part", "energy.csv.part", "t.h5"}) {
    const fs::path out = d / ("out-" + name);
    fs::create_directories(out);
    const fs::path fifo = out / name;
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expectRefused(bin("membrane") + " run '" + case_file + "' --out '" + out.string() + "'",
                  fifo, "FIFO");
    EXPECT_TRUE(fs::is_fifo(fifo)) << name;
  }
}
