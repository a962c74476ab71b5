// A run killed (kill -9) while it replaced one of its files leaves the
// temporary beside it ("<file>.tmp.<suffix>": the .xdmf index rewritten
// after every field step, summary.json, checkpoint.h5). The next run into
// the folder, fresh or a restart, removes them, and only them.
#include "restart_helpers.hpp"

#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <fstream>

using namespace lamina::membrane;
namespace fs = std::filesystem;

namespace {
/// An explicit run (the scheme the kill was seen on), fields every step.
const std::string kCase = test::isotropicSquare(4) +
                          "[time]\nintegrator = \"explicit\"\nt_end = 1.0e-3\n"
                          "[[fixed]]\nnodes = \"edges\"\n[[strike]]\nat = [0.5, 0.5]\n"
                          "speed = 1.0\n[output]\nfield_every = 1\n";

/// Files of @p dir as written by a killed run, plus bystanders; @return the debris.
std::vector<fs::path> litter(const fs::path& dir, const std::string& stem) {
  fs::create_directories(dir);
  const std::vector<fs::path> debris{dir / (stem + ".xdmf.tmp.4242"),
                                     dir / (stem + ".xdmf.tmp.aB3xYz"), dir / "summary.json.tmp.77",
                                     dir / "checkpoint.h5.tmp.9"};
  for (const auto& p : debris)
    std::ofstream(p) << "half a file";
  for (const char* keep : {"notes.txt", "other.xdmf.tmp.1", "my.xdmf.tmp"})
    std::ofstream(dir / keep) << "not ours";
  return debris;
}

void expectSwept(const fs::path& dir, const std::vector<fs::path>& debris) {
  for (const auto& p : debris)
    EXPECT_FALSE(fs::exists(p)) << p;
  for (const char* keep : {"notes.txt", "other.xdmf.tmp.1", "my.xdmf.tmp"})
    EXPECT_TRUE(fs::exists(dir / keep)) << keep << " is not debris of this run";
}
} // namespace

TEST(RunDebris, FreshRunAndRestartSweepTemporariesOfTheirFiles) {
  const Model model = test::modelFromText(kCase, "debris.toml");
  const test::Folder dir("run-debris");
  RunOptions opt;
  opt.out_dir = dir.path / "run";
  opt.quiet = true;
  opt.stop_at_step = 2;
  auto debris = litter(opt.out_dir, model.name);
  runModel(model, opt);
  expectSwept(opt.out_dir, debris);
  debris = litter(opt.out_dir, model.name);
  opt.stop_at_step = 0;
  opt.restart = true;
  runModel(model, opt);
  expectSwept(opt.out_dir, debris);
  EXPECT_TRUE(fs::exists(opt.out_dir / (model.name + ".xdmf")));
}
