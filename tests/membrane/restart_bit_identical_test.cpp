// Checkpoint and restart: a run of n steps stopped at step k and
// continued from its checkpoint writes the same outputs as the run that was
// never stopped, bit for bit: every value of probes.csv, energy.csv,
// reactions.csv, summary.json (timings aside) and of the field series is
// compared as the bytes of the double (memcmp), not to a tolerance. The
// reference is the uninterrupted run itself: the claim is identity, so no
// other number can stand in for it.
#include "restart_helpers.hpp"

#include "core/interrupt.hpp"
#include "membrane/io/checkpoint.hpp"
#include "membrane/run.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <csignal>
#include <sys/wait.h>

using namespace lamina::membrane;
namespace fs = std::filesystem;

namespace {

/// The linear model on the paper's Newmark scheme with everything that
/// carries history between steps: HHT-alpha (forces at t_n), implicit drag,
/// CG started from the projection on past solutions, a pressure pulse,
/// constraints (reactions), fields every 3 and energies every 2 steps.
const char* kLinear = R"(
[mesh]
Lx = 1.0
nx = 8
[[section]]
E = 1.0e9
nu = 0.3
density = 1000.0
thickness = 1.0e-3
[time]
dt = 1.0e-4
t_end = 4.0e-3
hht_alpha = -0.05
[solver]
type = "cg"
tolerance = 1.0e-12
projection = 3
[[fixed]]
nodes = "edges"
[[load]]
type = "pressure"
value = 1.0e3
profile = "pulse"
duration = 1.0e-3
[[drag]]
cd = 1.5
velocity = "resultant"
[[probe]]
name = "centre"
at = [0.5, 0.5]
[output]
field_every = 3
energy_every = 2
)";

/// The large-deflection fabric on explicit central differences: tension
/// only (wrinkling), a failure threshold crossed by elements before and
/// after the stop, a blast (arrival time, follower pressure), drag and
/// mass-proportional damping; 64 steps.
const char* kLargeDeflection = R"(
model = "large_deflection"
[mesh]
type = "rectangle"
Lx = 1.0
nx = 8
[[section]]
E = 580.0e6
nu = 0.3
density = 1280.0
thickness = 0.53e-3
tension_only = true
failure_strain = 2.0e-3
[time]
integrator = "explicit"
safety = 0.5
damping = 5.0
t_end = 4.0e-3
[[fixed]]
nodes = "edges"
[[blast]]
charge = 0.05
position = [0.5, 0.5, -1.5]
burst = "hemispherical"
[[drag]]
cd = 1.5
velocity = "resultant"
[[probe]]
name = "centre"
at = [0.5, 0.5]
[output]
field_every = 7
energy_every = 3
)";

/// A GVBO polyurea sheet (the catalog's, a law with history at every
/// element), tension only, struck: the history blocks, the adaptive step and
/// the law's dissipation must continue bit for bit; 40-odd steps.
const char* kGvbo = R"(
model = "large_deflection"
[mesh]
type = "rectangle"
Lx = 0.2
nx = 6
[[section]]
material = "polyurea-gvbo"
thickness = 1.0e-3
tension_only = true
[time]
integrator = "explicit"
safety = 0.5
t_end = 6.0e-4
[[fixed]]
nodes = "edges"
[initial]
velocity = [0.0, 0.0, 20.0]
[[probe]]
name = "centre"
at = [0.1, 0.1]
[output]
field_every = 7
energy_every = 3
)";

/// The large-deflection membrane with rigid surfaces that carry state: a
/// free sphere (its position and velocity) dropped on it and a plane with
/// friction under it, contact damping, gravity; the stop falls during the
/// sphere's contact.
const char* kContact = R"(
model = "large_deflection"
[mesh]
type = "rectangle"
Lx = 1.0
nx = 10
[[section]]
E = 1.0e6
nu = 0.3
density = 100.0
thickness = 1.0e-3
prestress = 100.0
[time]
integrator = "explicit"
safety = 0.5
t_end = 0.03
[[fixed]]
nodes = "edges"
[gravity]
g = [0.0, 0.0, -9.81]
[[rigid_surface]]
name = "ball"
shape = "sphere"
center = [0.5, 0.5, 0.102]
radius = 0.1
mass = 0.1
velocity = [0.3, 0.0, -2.0]
penalty = 1.0e4
friction = 0.2
contact_damping = 0.1
penetration_tolerance = 0.01
[[rigid_surface]]
name = "floor"
shape = "plane"
point = [0.0, 0.0, -0.01]
normal = [0.0, 0.0, 1.0]
penalty = 1.0e4
friction = 0.5
penetration_tolerance = 0.05
[[probe]]
name = "centre"
at = [0.5, 0.5]
[output]
field_every = 7
energy_every = 3
)";

/// Runs @p model uninterrupted into DIR/full; @return its options.
RunOptions runFull(const Model& model, const fs::path& dir, long& steps) {
  RunOptions full;
  full.out_dir = dir / "full";
  full.quiet = true;
  steps = runModel(model, full)["steps"].get<long>();
  return full;
}

/// Runs @p model uninterrupted into "full", and stopped at @p stop then
/// restarted into "split"; expects the same outputs bit for bit.
void expectRestartIdentical(const std::string& text, long stop, const std::string& name) {
  const Model model = test::modelFromText(text, name + ".toml");
  const test::Folder dir(name);
  long steps = 0;
  const RunOptions full = runFull(model, dir.path, steps);
  ASSERT_GT(steps, stop) << "the stop must fall inside the run";

  RunOptions split = full;
  split.out_dir = dir.path / "split";
  split.stop_at_step = stop;
  const auto first = runModel(model, split);
  ASSERT_EQ(first["steps"].get<long>(), stop);
  ASSERT_TRUE(fs::exists(checkpointPath(split.out_dir)));
  split.stop_at_step = 0;
  split.restart = true;
  runModel(model, split);
  test::expectSameOutputs(full.out_dir, split.out_dir, model.name);
}

} // namespace

TEST(Restart, LinearNewmarkContinuesBitIdentically) {
  expectRestartIdentical(kLinear, 23, "restart-linear");
}

TEST(Restart, LargeDeflectionExplicitContinuesBitIdentically) {
  // Elements fail from step 43 on: the stop at 47 splits the failure history.
  expectRestartIdentical(kLargeDeflection, 47, "restart-large");
}

TEST(Restart, GvboSectionsContinueBitIdentically) {
  expectRestartIdentical(kGvbo, 17, "restart-gvbo");
  // The stop falls after a change of step (the sheet's tension shortens it):
  // the checkpoint holds a step base k > 0, which the restart must continue.
  const Model model = test::modelFromText(kGvbo, "restart-gvbo.toml");
  const test::Folder dir("restart-gvbo-base");
  RunOptions o;
  o.out_dir = dir.path;
  o.quiet = true;
  o.stop_at_step = 17;
  runModel(model, o);
  const Checkpoint c = readCheckpoint(checkpointPath(dir.path));
  const Eigen::VectorXd& step = c.data.at("integrator/step");
  EXPECT_GT(step[2], 0.0) << "no change of step before the stop";
}

TEST(Restart, ContactWithAFreeSphereContinuesBitIdentically) {
  const Model model = test::modelFromText(kContact, "restart-contact.toml");
  const test::Folder dir("restart-contact-probe");
  long steps = 0;
  runFull(model, dir.path, steps);
  expectRestartIdentical(kContact, steps / 2, "restart-contact");
}

// kill -9 after a periodic checkpoint: the tables already hold rows written
// after it (and are still ".part" files), and a later checkpoint write left
// its temporary. The restart cuts the tables back to the checkpoint's step,
// removes the temporary and ends identical to the uninterrupted run.
TEST(Restart, RowsWrittenAfterTheLastCheckpointAreCutBack) {
  const Model model = test::modelFromText(kLinear, "restart-crash.toml");
  const test::Folder dir("restart-crash");
  long steps = 0;
  const RunOptions full = runFull(model, dir.path, steps);
  ASSERT_GT(steps, 27);

  Model periodic = model;
  periodic.output.checkpoint_every = 10;
  RunOptions split = full;
  split.out_dir = dir.path / "split";
  split.stop_at_step = 20; // checkpoints at 10 and 20
  runModel(periodic, split);
  const fs::path ck = checkpointPath(split.out_dir);
  fs::copy_file(ck, dir.path / "at20.h5");
  split.restart = true;
  split.stop_at_step = 27; // rows and field steps 21..27 written...
  runModel(periodic, split);
  fs::copy_file(dir.path / "at20.h5", ck, fs::copy_options::overwrite_existing);
  for (const char* f : {"probes.csv", "energy.csv", "reactions.csv"}) // ...and died before closing
    fs::rename(split.out_dir / f, split.out_dir / (std::string(f) + ".part"));
  const fs::path debris = split.out_dir / "checkpoint.h5.tmp.99999"; // died writing a checkpoint
  std::ofstream(debris) << "half a checkpoint";
  // Field steps 0, 3, ..., 27 are /steps/0..9; the checkpoint at 20 holds
  // 0..6. Continued only to step 22 (one field step, 21), the series must
  // hold /steps/0..7 as an uninterrupted run stopped there does, not the
  // orphans 8 and 9 (24, 27) of the crashed run.
  split.stop_at_step = 22;
  runModel(periodic, split);
  {
    const std::string index = lamina::test::slurp(split.out_dir / (model.name + ".xdmf"));
    std::size_t listed = 0;
    for (auto at = index.find("<Grid Name=\"step"); at != std::string::npos;
         at = index.find("<Grid Name=\"step", at + 1))
      ++listed;
    EXPECT_EQ(listed, 8u);
    const lamina::core::H5File h5(split.out_dir / (model.name + ".h5"),
                                  lamina::core::H5File::Mode::ReadOnly);
    EXPECT_TRUE(h5.exists("/steps/7"));
    EXPECT_FALSE(h5.exists("/steps/8")) << "orphan field step of the crashed run";
    EXPECT_FALSE(h5.exists("/steps/9")) << "orphan field step of the crashed run";
  }
  split.stop_at_step = 0;
  runModel(periodic, split);
  test::expectSameOutputs(full.out_dir, split.out_dir, model.name);
  for (const auto& f : fs::directory_iterator(split.out_dir))
    EXPECT_NE(f.path().extension(), ".part") << f.path();
  EXPECT_FALSE(fs::exists(debris));
}

// The checkpoint records the OpenMP thread count: a restart with another
// one continues (a warning, not an error) and says that bit identity is not
// guaranteed; with the same count it says nothing.
TEST(Restart, AnotherThreadCountIsWarnedAbout) {
  const Model model = test::modelFromText(kLinear, "restart-threads.toml");
  const test::Folder dir("restart-threads");
  RunOptions opt;
  opt.out_dir = dir.path / "run";
  opt.quiet = true;
  opt.stop_at_step = 4;
  const int threads = omp_get_max_threads();
  runModel(model, opt);
  opt.restart = true;
  opt.stop_at_step = 6;
  ::testing::internal::CaptureStderr();
  runModel(model, opt);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  omp_set_num_threads(threads + 1);
  opt.stop_at_step = 8;
  ::testing::internal::CaptureStderr();
  runModel(model, opt);
  const std::string said = ::testing::internal::GetCapturedStderr();
  omp_set_num_threads(threads);
  EXPECT_NE(said.find("warning: " + checkpointPath(opt.out_dir).string()), std::string::npos)
      << said;
  EXPECT_NE(said.find("not guaranteed to be bit-identical"), std::string::npos) << said;
}

// The program stopped by SIGTERM mid-run (exit 143, checkpoint written on the
// way out), then `membrane run CASE --restart DIR`: the outputs equal those
// of the uninterrupted program run.
TEST(Restart, RunInterruptedBySigtermContinuesBitIdentically) {
  const test::Folder dir("restart-signal");
  auto args = [&](const fs::path& out, const std::string& flag) {
    return std::vector<std::string>{"run",   test::sourcePath("cases/membrane/case3.toml").string(),
                                    flag,    out.string(),
                                    "--set", "time.t_end=0.01",
                                    "--set", "output.field_every=40"};
  };
  const fs::path full = dir.path / "full", split = dir.path / "split";
  auto r = lamina::test::run(test::membraneCommand(args(full, "--out")));
  ASSERT_EQ(r.code, 0) << r.output;

  auto argv = args(split, "--out");
  argv.insert(argv.begin(), (lamina::test::kBin / "membrane").string());
  const pid_t pid = lamina::test::spawn(argv);
  ASSERT_GT(pid, 0);
  for (int i = 0; i < 6000 && !fs::exists(split / "probes.csv.part"); ++i)
    ::usleep(5000); // stepping has started (generous on a loaded machine)
  ::kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping";
  ASSERT_EQ(WEXITSTATUS(status), 143) << "the run ended before the signal: make it longer";
  ASSERT_TRUE(fs::exists(checkpointPath(split)));

  r = lamina::test::run(test::membraneCommand(args(split, "--restart")));
  ASSERT_EQ(r.code, 0) << r.output;
  test::expectSameOutputs(full, split, "case3");
}

namespace {

/// @return DIR/summary.json
nlohmann::json summaryOf(const fs::path& dir) {
  return nlohmann::json::parse(lamina::test::slurp(dir / "summary.json"));
}

/// @return the step of the checkpoint in @p dir
long checkpointStep(const fs::path& dir) {
  return static_cast<long>(readCheckpoint(checkpointPath(dir)).data.at("state/time")[1]);
}

/// Runs @p model with @p opt under an interrupt guard after a SIGINT (the
/// run stops after its next step); @return the folder the message says to
/// continue with (`--restart DIR`).
fs::path interruptedRestartFolder(const Model& model, const RunOptions& opt) {
  std::string message;
  {
    const lamina::core::InterruptGuard guard;
    std::raise(SIGINT);
    try {
      runCase(model, opt);
      ADD_FAILURE() << "the run was not interrupted";
    } catch (const lamina::Interrupted& e) {
      message = e.what();
    }
  }
  { const lamina::core::InterruptGuard clear; } // the next run does not see the signal
  const std::string key = "(continue with --restart ";
  const auto at = message.find(key);
  if (at == std::string::npos || message.back() != ')') {
    ADD_FAILURE() << message;
    return {};
  }
  return message.substr(at + key.size(), message.size() - 1 - at - key.size());
}

} // namespace

// A compare_without_drag case runs twice (DIR/with-drag, DIR/without-drag),
// each run with its own checkpoint: stopped in the first run, then in the
// second, then interrupted by SIGINT in each, and every time continued with
// `--restart DIR`, it ends with the outputs of the uninterrupted case bit
// for bit: every table and field of both runs, both summaries and the
// case's summary.json with its drag_comparison (timings aside).
TEST(Restart, DragComparisonContinuesBitIdentically) {
  const Model model = test::dragComparisonCase();
  const test::Folder dir("restart-compare");
  RunOptions full;
  full.out_dir = dir.path / "full";
  full.quiet = true;
  ASSERT_EQ(runCase(model, full)["steps"].get<long>(), 30);

  RunOptions split = full;
  split.out_dir = dir.path / "split";
  split.stop_at_step = 10; // a fresh run: the first run stops
  auto s = runCase(model, split);
  EXPECT_EQ(s["stopped_run"], "with-drag");
  EXPECT_EQ(s["stopped_at_step"], 10);
  EXPECT_EQ(summaryOf(split.out_dir), s);
  EXPECT_EQ(checkpointStep(split.out_dir / "with-drag"), 10);
  EXPECT_FALSE(fs::exists(split.out_dir / "without-drag")) << "the second run started";

  split.restart = true;
  split.stop_at_step = 5; // the first run is past step 5: it ends, the second stops there
  Model periodic = model; // periodic checkpoints, each run in its own folder
  periodic.output.checkpoint_every = 4;
  s = runCase(periodic, split);
  EXPECT_EQ(s["stopped_run"], "without-drag");
  EXPECT_EQ(s["stopped_at_step"], 5);
  EXPECT_EQ(checkpointStep(split.out_dir / "with-drag"), 28);
  EXPECT_EQ(checkpointStep(split.out_dir / "without-drag"), 5);
  EXPECT_FALSE(summaryOf(split.out_dir / "with-drag").contains("stopped_at_step"));

  split.stop_at_step = 12; // the first run has ended: the second continues to 12
  s = runCase(model, split);
  EXPECT_EQ(s["stopped_run"], "without-drag");
  EXPECT_EQ(checkpointStep(split.out_dir / "with-drag"), 28) << "the ended run ran again";

  split.stop_at_step = 0; // SIGINT in the second run: continue with the folder it names
  EXPECT_EQ(interruptedRestartFolder(model, split), split.out_dir);
  s = summaryOf(split.out_dir);
  EXPECT_EQ(s["stopped_run"], "without-drag");
  EXPECT_EQ(s["signal"], "SIGINT");
  EXPECT_EQ(checkpointStep(split.out_dir / "without-drag"), 13);

  runCase(model, split);
  for (const char* run : {"with-drag", "without-drag"})
    test::expectSameOutputs(full.out_dir / run, split.out_dir / run, model.name);
  const auto a = summaryOf(full.out_dir), b = summaryOf(split.out_dir);
  ASSERT_TRUE(b.contains("drag_comparison"));
  EXPECT_FALSE(b.contains("stopped_run"));
  test::expectSameJson(a, b, "summary.json");

  // SIGINT in the first run of a fresh case, continued with the folder it names.
  RunOptions fresh = full;
  fresh.out_dir = dir.path / "fresh";
  const fs::path again = interruptedRestartFolder(model, fresh);
  EXPECT_EQ(again, fresh.out_dir);
  EXPECT_EQ(summaryOf(fresh.out_dir)["stopped_run"], "with-drag");
  fresh.out_dir = again;
  fresh.restart = true;
  runCase(model, fresh);
  for (const char* run : {"with-drag", "without-drag"})
    test::expectSameOutputs(full.out_dir / run, fresh.out_dir / run, model.name);
  test::expectSameJson(a, summaryOf(fresh.out_dir), "summary.json");
}
