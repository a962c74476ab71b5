// Restarts that cannot continue : no checkpoint in the folder, a
// truncated or corrupted checkpoint, a checkpoint of another case, outputs
// that are gone, the folder of one run of a case that runs twice. Each is a
// clear error naming the file, never a crash or a run that silently starts
// over.
#include "restart_helpers.hpp"

#include "membrane/io/checkpoint.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

using namespace lamina::membrane;
namespace fs = std::filesystem;

namespace {

using test::strikeCase;

/// A folder holding a run of strikeCase() stopped at step 10 with its checkpoint.
struct Stopped {
  Stopped() : model(test::modelFromText(strikeCase(), "stopped.toml")), dir("restart-bad") {
    opt.out_dir = dir.path / "run";
    opt.quiet = true;
    opt.stop_at_step = 10;
    runModel(model, opt);
    opt.stop_at_step = 0;
    opt.restart = true;
  }
  /// @return the message of the restart's error ("" when it ran)
  std::string restartError() const {
    try {
      runModel(model, opt);
    } catch (const lamina::Error& e) {
      return e.what();
    }
    return "";
  }
  Model model;
  test::Folder dir;
  RunOptions opt;
};

/// Expects @p message to hold @p file and every one of @p parts.
void expectNames(const std::string& message, const fs::path& file,
                 const std::vector<std::string>& parts) {
  ASSERT_FALSE(message.empty()) << "the restart ran";
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  for (const auto& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << "no '" << p << "' in: " << message;
}

} // namespace

TEST(MalformedRestart, MissingFolderOrCheckpointNamesTheFile) {
  const test::Folder dir("restart-missing");
  const Model model = test::modelFromText(strikeCase(), "missing.toml");
  RunOptions opt;
  opt.out_dir = dir.path / "never-ran";
  opt.quiet = true;
  opt.restart = true;
  std::string message;
  try {
    runModel(model, opt);
  } catch (const lamina::Error& e) {
    message = e.what();
  }
  expectNames(message, opt.out_dir, {"no output folder"});
  EXPECT_FALSE(fs::exists(opt.out_dir)) << "a failed restart must not create the folder";
  fs::create_directories(opt.out_dir); // a folder without a checkpoint
  message.clear();
  try {
    runModel(model, opt);
  } catch (const lamina::Error& e) {
    message = e.what();
  }
  expectNames(message, checkpointPath(opt.out_dir), {"no checkpoint"});
  // The program: exit 1 and the folder named.
  const auto r = lamina::test::run(
      test::membraneCommand({"run", test::sourcePath("cases/membrane/case3.toml").string(),
                             "--restart", (dir.path / "nowhere").string()}));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find((dir.path / "nowhere").string()), std::string::npos) << r.output;
}

TEST(MalformedRestart, TruncatedCheckpointIsRefused) {
  Stopped run;
  const fs::path ck = checkpointPath(run.opt.out_dir);
  fs::resize_file(ck, fs::file_size(ck) / 2);
  expectNames(run.restartError(), ck, {"unreadable"});
}

// A flipped byte inside the saved displacements: HDF5 reads it without
// complaint (it keeps no checksum of raw data); ours catches it.
TEST(MalformedRestart, CorruptedCheckpointIsRefused) {
  Stopped run;
  const fs::path ck = checkpointPath(run.opt.out_dir);
  const Eigen::VectorXd u = readCheckpoint(ck).data.at("state/u");
  const auto nz = std::find_if(u.data(), u.data() + u.size(), [](double x) { return x != 0; });
  ASSERT_NE(nz, u.data() + u.size()) << "the struck node has moved";
  std::string bytes = test::slurp(ck);
  const auto at = bytes.find(std::string(reinterpret_cast<const char*>(nz), sizeof(double)));
  ASSERT_NE(at, std::string::npos);
  bytes[at + 3] = static_cast<char>(bytes[at + 3] ^ 0x10);
  std::ofstream(ck, std::ios::binary | std::ios::trunc) << bytes;
  expectNames(run.restartError(), ck, {"corrupt"});
}

TEST(MalformedRestart, CheckpointOfAnotherCaseIsRefused) {
  Stopped run;
  run.opt.case_digest = "another";
  expectNames(run.restartError(), checkpointPath(run.opt.out_dir), {"another case"});
  // Through the program: the same case file with another --set is another case.
  const test::Folder dir("restart-other");
  const std::string c3 = test::sourcePath("cases/membrane/case3.toml").string();
  const std::string out = (dir.path / "run").string();
  const std::string ck = checkpointPath(out).string();
  auto membrane = [](const std::vector<std::string>& args) {
    return lamina::test::run(test::membraneCommand(args));
  };
  auto r = membrane({"run", c3, "--out", out, "--stop-at-step", "3"});
  ASSERT_EQ(r.code, 0) << r.output;
  for (const auto& args :
       {std::vector<std::string>{"run", c3, "--restart", out, "--set", "time.t_end=1.0e-4"},
        std::vector<std::string>{"run", test::sourcePath("cases/membrane/case4.toml").string(),
                                 "--restart", out}}) {
    r = membrane(args);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(ck), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("another case"), std::string::npos) << r.output;
  }
  // output.checkpoint_every does not change the results: the same case.
  r = membrane(
      {"run", c3, "--restart", out, "--set", "output.checkpoint_every=50", "--stop-at-step", "5"});
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(MalformedRestart, MissingOutputTableIsNamed) {
  Stopped run;
  fs::remove(run.opt.out_dir / "probes.csv");
  expectNames(run.restartError(), run.opt.out_dir / "probes.csv", {"neither"});
}

TEST(MalformedRestart, NegativeCheckpointIntervalIsRefused) {
  try {
    test::modelFromText(strikeCase() + "[output]\ncheckpoint_every = -1\n", "bad.toml");
    FAIL() << "accepted";
  } catch (const lamina::Error& e) {
    EXPECT_NE(std::string(e.what()).find("output.checkpoint_every"), std::string::npos) << e.what();
  }
}

// A compare_without_drag case (two runs, DIR/with-drag and DIR/without-drag,
// each with its checkpoint) continues from DIR: the folder of one of its
// runs is refused naming DIR, a missing checkpoint and a checkpoint of the
// other run are named, and a --stop-at-step no run takes is refused before
// anything runs.
TEST(MalformedRestart, DragComparisonRestartsFromTheCaseFolder) {
  const Model model = test::dragComparisonCase();
  const test::Folder dir("restart-compare-bad");
  RunOptions opt;
  opt.out_dir = dir.path / "case";
  opt.quiet = true;
  opt.restart = true;
  auto error = [&] {
    try {
      runCase(model, opt);
    } catch (const lamina::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  expectNames(error(), opt.out_dir, {"no output folder"});
  EXPECT_FALSE(fs::exists(opt.out_dir)) << "a failed restart must not create the folder";

  opt.restart = false;
  opt.stop_at_step = 31; // 30 steps
  expectNames(error(), "--stop-at-step 31", {"not one of the steps 1 to 30"});
  EXPECT_FALSE(fs::exists(opt.out_dir / "with-drag" / "probes.csv")) << "it ran";
  opt.stop_at_step = 10;
  runCase(model, opt);
  opt.stop_at_step = 5; // the first run ends, the second stops at 5
  opt.restart = true;
  runCase(model, opt);
  opt.stop_at_step = 0;

  const fs::path case_dir = opt.out_dir;
  opt.out_dir = case_dir / "without-drag";
  expectNames(error(), opt.out_dir,
              {"one of the two runs", "restart with the case's folder " + case_dir.string()});
  opt.out_dir = case_dir;
  const fs::path ck = checkpointPath(case_dir / "without-drag");
  fs::copy_file(checkpointPath(case_dir / "with-drag"), ck, fs::copy_options::overwrite_existing);
  expectNames(error(), ck, {"another case"});
  fs::remove(ck);
  expectNames(error(), ck, {"no checkpoint"});
}
