// Checkpoints whose stored values were edited and whose checksum was
// recomputed to match (writeCheckpoint computes it, as a hostile editor
// would): the checksum no longer protects them, so every count, index, time
// and size is checked against the case and the files it names. Each edit is
// refused by a restart with an error naming the checkpoint file and the
// entry, never a crash, an endless loop or a run on nonsense.
#include "restart_helpers.hpp"

#include "membrane/io/checkpoint.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

using namespace lamina::membrane;
namespace fs = std::filesystem;

namespace {

/// A run of the struck square (30 Newmark steps, a probe, reactions,
/// fields every 3 and energies every 2 steps) stopped at step 10 with its
/// checkpoint, kept
/// aside so that each edit starts from the original.
class EditedCheckpoint : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    dir_ = new test::Folder("checkpoint-edits");
    model_ = new Model(test::modelFromText(
        test::strikeCase("[output]\nfield_every = 3\nenergy_every = 2\n"), "edited.toml"));
    RunOptions opt;
    opt.out_dir = dir_->path / "run";
    opt.quiet = true;
    opt.stop_at_step = 10;
    runModel(*model_, opt);
    fs::copy(opt.out_dir, dir_->path / "original", fs::copy_options::recursive);
  }
  static void TearDownTestSuite() {
    delete model_;
    delete dir_;
  }
  /// Puts the stopped run's folder back as it was.
  static void reset() {
    fs::remove_all(out());
    fs::copy(dir_->path / "original", out(), fs::copy_options::recursive);
  }
  static fs::path out() { return dir_->path / "run"; }
  static fs::path file() { return checkpointPath(out()); }

  /// Applies @p edit to the checkpoint's entries, writes it back with its
  /// checksum recomputed, restarts; @return the restart's error ("" if it ran).
  static std::string restartAfter(const std::function<void(History&)>& edit) {
    reset();
    Checkpoint c = readCheckpoint(file());
    edit(c.data);
    writeCheckpoint(file(), c);
    return restartError();
  }
  /// @return the error of restarting from the folder as it is ("" if it ran)
  static std::string restartError() {
    RunOptions opt;
    opt.out_dir = out();
    opt.quiet = true;
    opt.restart = true;
    try {
      runModel(*model_, opt);
    } catch (const lamina::Error& e) {
      return e.what();
    }
    return "";
  }
  /// Expects the restart after @p edit refused, naming the checkpoint and @p entry.
  static void expectRefused(const std::function<void(History&)>& edit, const std::string& entry,
                            const std::string& also = "") {
    const std::string e = restartAfter(edit);
    ASSERT_FALSE(e.empty()) << "the edited checkpoint ran (" << entry << ")";
    EXPECT_NE(e.find(file().string()), std::string::npos) << e;
    EXPECT_NE(e.find("'" + entry + "'"), std::string::npos) << e;
    EXPECT_NE(e.find(also), std::string::npos) << e;
  }
  static test::Folder* dir_;
  static Model* model_;
};

test::Folder* EditedCheckpoint::dir_ = nullptr;
Model* EditedCheckpoint::model_ = nullptr;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

} // namespace

TEST_F(EditedCheckpoint, UneditedCheckpointRestarts) {
  EXPECT_EQ(restartAfter([](History&) {}), "");
}

// Step counts: beyond the case's 30 steps (a huge count looped forever: the
// double did not fit a long), negative, fractional; a time that is not step * dt.
TEST_F(EditedCheckpoint, StepCountAndTimeAreCheckedAgainstTheCase) {
  for (const double step : {1e30, 31.0, -5.0, 10.5, kNan})
    expectRefused([&](History& h) { h["state/time"][1] = step; }, "state/time");
  expectRefused([](History& h) { h["state/time"][0] *= 1.5; }, "state/time", "step * dt");
  // Step, time and field times edited together, consistently: the field
  // series holds the steps of step 10, not those of step 15.
  const std::string e = restartAfter([](History& h) {
    const double dt = h["integrator/dt"][0];
    h["state/time"] = Eigen::Vector2d(15 * dt, 15.0);
    Eigen::VectorXd& times = h["run/field_times"]; // steps 0, 3, 6, 9 -> also 12, 15
    times.conservativeResize(6);
    times.tail(2) << 12 * dt, 15 * dt;
  });
  EXPECT_NE(e.find((out() / "edited.h5").string()), std::string::npos) << e;
  EXPECT_NE(e.find("'run/field_times' of " + file().string()), std::string::npos) << e;
}

// Array sizes against the model's DOFs, constraints and probes.
TEST_F(EditedCheckpoint, SizesAreCheckedAgainstTheModel) {
  for (const char* key :
       {"state/u", "state/v", "state/a", "integrator/a_prev", "integrator/forces/external",
        "integrator/forces/reaction", "run/probe_peak", "run/peak_reaction", "works"})
    expectRefused(
        [&](History& h) {
          Eigen::VectorXd& v = h.at(key);
          v.conservativeResize(v.size() + 7);
          v.tail(7).setZero();
        },
        key, "values");
  // A force the scheme does not have (springs on a case without springs).
  expectRefused([](History& h) { h["integrator/forces/spring"] = h["state/u"]; },
                "integrator/forces/spring");
  expectRefused([](History& h) { h.erase("integrator/forces/reaction"); },
                "integrator/forces/reaction");
}

// Per-node and per-element entries are in the run's node order: a checkpoint
// without the order's fingerprint (an older build) or with another one is refused.
TEST_F(EditedCheckpoint, AnotherNodeOrderIsRefused) {
  expectRefused([](History& h) { h.erase("mesh/order"); }, "mesh/order", "another order");
  expectRefused([](History& h) { h["mesh/order"][0] += 1; }, "mesh/order", "another order");
}

TEST_F(EditedCheckpoint, NonFiniteValuesAreRefused) {
  for (const char* key : {"state/v", "works", "run/last_energy", "integrator/forces/drag"})
    expectRefused([&](History& h) { h.at(key)[0] = kNan; }, key, "not finite");
  expectRefused([](History& h) { h.at("state/u")[2] = std::numeric_limits<double>::infinity(); },
                "state/u", "not finite");
}

// Indices and counts: the failure record's element and criterion, the
// solver's counts, the maxima, the thread count.
TEST_F(EditedCheckpoint, IndicesAndCountsAreInRange) {
  for (const double e : {32.0, 1e9, -2.0, 0.5})
    expectRefused([&](History& h) { h["failure/first"][0] = e; }, "failure/first");
  expectRefused([](History& h) { h["failure/first"][2] = 7; }, "failure/first");
  expectRefused([](History& h) { h["failure/first"] = Eigen::Vector3d(3, 1.0, 1); },
                "failure/first", "failure time");
  for (const int k : {0, 1, 2})
    expectRefused([&](History& h) { h["integrator/solver/counts"][k] = -1; },
                  "integrator/solver/counts");
  expectRefused([](History& h) { h["integrator/solver/counts"][2] = 1; },
                "integrator/solver/counts"); // projection is 0: no basis kept
  expectRefused([](History& h) { h["integrator/last_iterations"][0] = 1e40; },
                "integrator/last_iterations");
  expectRefused([](History& h) { h["run/maxima"][1] = -1; }, "run/maxima");
  expectRefused([](History& h) { h["run/omp_threads"][0] = 1e12; }, "run/omp_threads");
}

// The tables and the field series it resumes: byte counts that cut a row,
// that hold another number of rows, that are not sizes at all; field times
// that are not those of the case's field steps.
TEST_F(EditedCheckpoint, TableSizesAndFieldTimesMatchTheOutputs) {
  for (const double bytes : {-1.0, 1e300, 0.5})
    expectRefused([&](History& h) { h["run/csv_bytes"][0] = bytes; }, "run/csv_bytes");
  const auto cut = [](History& h) { h["run/csv_bytes"][1] -= 5; };
  const std::string e = restartAfter(cut);
  EXPECT_NE(e.find((out() / "energy.csv.part").string()), std::string::npos) << e;
  EXPECT_NE(e.find("inside a row"), std::string::npos) << e;
  EXPECT_NE(e.find(file().string()), std::string::npos) << e;
  // Bytes that end a row, but hold the rows of step 5, not of step 10.
  const std::string rows = restartAfter([](History& h) {
    const std::string table = test::slurp(out() / "probes.csv"); // closed at the stop
    std::size_t at = 0;
    for (int line = 0; line < 6; ++line) // the header and 5 rows
      at = table.find('\n', at) + 1;
    h["run/csv_bytes"][0] = static_cast<double>(at);
  });
  EXPECT_NE(rows.find((out() / "probes.csv.part").string()), std::string::npos) << rows;
  EXPECT_NE(rows.find("6 lines"), std::string::npos) << rows;
  EXPECT_NE(rows.find("'run/csv_bytes' of " + file().string()), std::string::npos) << rows;
  expectRefused([](History& h) { h["run/field_times"][2] *= 1.0000001; }, "run/field_times");
  expectRefused(
      [](History& h) {
        Eigen::VectorXd& v = h["run/field_times"];
        v.conservativeResize(v.size() - 1);
      },
      "run/field_times");
}

// The container itself: the size of the stored float type corrupted (to
// 4294901913 bytes per value, found by fuzz/checkpoint_fuzzer.cpp): HDF5
// then allocated gigabytes to read 27 doubles. Any damaged byte of the
// container is now refused by the checksum in the checkpoint's header before
// HDF5 parses the file (HDF5 1.10 also read freed memory on a corrupt
// attribute message, found by the same fuzzer).
TEST_F(EditedCheckpoint, CorruptedTypeSizeIsRefusedBeforeReading) {
  reset();
  std::string bytes = test::slurp(file());
  // HDF5's datatype message of an IEEE little-endian double: class 1
  // (version 1), bit field 0x20 0x3f 0x00, size 8 (4 bytes).
  const std::string f64("\x11\x20\x3f\x00\x08\x00\x00\x00", 8);
  std::size_t patched = 0;
  for (auto at = bytes.find(f64); at != std::string::npos; at = bytes.find(f64, at + 1), ++patched)
    bytes.replace(at + 4, 4, std::string("\x99\xff\xfe\xff", 4));
  ASSERT_GT(patched, 0u) << "no double type message found";
  std::ofstream(file(), std::ios::binary | std::ios::trunc) << bytes;
  const std::string e = restartError(); // not std::bad_alloc, not gigabytes
  EXPECT_NE(e.find(file().string()), std::string::npos) << e;
  EXPECT_NE(e.find("do not match the checksum in its header"), std::string::npos) << e;
}

// The program: the edits that crashed (SIGSEGV: a reaction array of the
// wrong size) or looped forever (a huge step count) exit 1 naming the file.
TEST_F(EditedCheckpoint, ProgramExitsOneOnEditedCheckpoints) {
  const fs::path c3 = test::sourcePath("cases/membrane/case3.toml");
  const fs::path run = dir_->path / "program";
  const std::vector<std::string> args{"run", c3.string(), "--set", "time.t_end=1.0e-3"};
  auto with = [&](std::vector<std::string> a, const std::string& flag) {
    a.push_back(flag);
    a.push_back(run.string());
    return test::membraneCommand(a);
  };
  auto r = lamina::test::run(with(args, "--out") + " --stop-at-step 4");
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path ck = checkpointPath(run);
  const Checkpoint original = readCheckpoint(ck);
  for (const auto& edit : std::vector<std::function<void(History&)>>{
           [](History& h) { h["state/time"][1] = 1e300; },
           [](History& h) { h["integrator/forces/reaction"].conservativeResize(1); }}) {
    Checkpoint c = original;
    edit(c.data);
    writeCheckpoint(ck, c);
    r = lamina::test::run(with(args, "--restart"));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(ck.string()), std::string::npos) << r.output;
  }
}
