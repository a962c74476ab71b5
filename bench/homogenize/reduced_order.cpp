// Benchmark (not a test) of the reduced-order cell as a law: one material-
// point step of reduced-order library entries against one step of the
// full-field nonlinear cell on the same voxels, along the same history.
// The history: `materials drive`'s path at RATE to TO in STEPS steps (small
// strain, the kinematics of the FFT cell). Each entry's whole history is
// run again and again for at least MIN_SECONDS (the step time is its mean;
// ConstitutiveLaw::update, the call a coarse solver makes per point), then
// the full-field cell (NonlinearHomogenizer, THREADS threads) runs the
// history once (its mean step wall time, FFTW plans made before).
// Besides the times, both sides' law updates per step are counted (not
// timed): the full field updates every voxel of a nonlinear phase once per
// Newton iteration and once more for the final residual; the reduced-order
// law every nonlinear partition once per Newton iteration and once more (a
// linear partition's stress is a 6x6 product, not counted on either side).
// Their ratio is what the step ratio would be if only the law updates cost
// time and an update cost the same on both sides (the same law code): a
// bound that the reduced model's own arithmetic can only lower.
// Usage: homogenize_rom_bench LIBRARY ENTRY[,ENTRY...] CELL [N [THREADS [PATH [RATE
//        [TO [STEPS [MIN_SECONDS [TOL]]]]]]]]
// Defaults: N 32, THREADS 1, confined, 2.6e3 /s, 0.3, 60 steps, 2 s, TOL the
// reduced-order law's Newton tolerance (ReducedOrderOptions, 1e-10; the
// full field converges to its own 1e-5, NonlinearOptions).
#include "homogenize/library_entry.hpp"
#include "homogenize/macro_history.hpp"
#include "homogenize/nonlinear_homogenizer.hpp"
#include "homogenize/nonlinear_run.hpp"
#include "materials/material_source.hpp"
#include "materials/reduced_order_law.hpp"
#include "micro/cell.hpp"
#include "micro/unit_cell.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

using namespace lamina;

namespace {

double seconds(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

/// Moves @p step on to history step @p s at time @p t (updated): the strain
/// of s (strain-controlled components only: the bench uses strain paths),
/// J = 1 + tr eps (small strain).
void advance(materials::PointStep& step, const homogenize::MacroStep& s, double& t) {
  step.eps_n = step.eps;
  for (int a = 0; a < 6; ++a)
    step.eps[a] = s.value[static_cast<std::size_t>(a)];
  step.J_n = 1 + step.eps_n.head<3>().sum();
  step.J = 1 + step.eps.head<3>().sum();
  step.dt = s.t - t;
  t = s.t;
}

/// Mean time of one law step over repeated runs of @p history.
double lawStep(const materials::ConstitutiveLaw& law, const homogenize::MacroHistory& history,
               double min_seconds, double& final_stress) {
  const int size = law.stateSize();
  std::vector<double> state(static_cast<std::size_t>(size));
  long steps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  do {
    law.initState(state.data());
    materials::PointStep step;
    double t = 0;
    materials::Vector6 sigma;
    for (const homogenize::MacroStep& s : history.steps) {
      advance(step, s, t);
      law.update(step, state.data(), state.data(), sigma, nullptr);
      ++steps;
    }
    final_stress = sigma.cwiseAbs().maxCoeff();
  } while (seconds(t0) < min_seconds);
  return seconds(t0) / static_cast<double>(steps);
}

/// Law updates per step of one run of @p history by @p law: (Newton
/// iterations + 1) x its nonlinear partitions.
double lawUpdatesPerStep(const materials::ReducedOrderLaw& law,
                         const homogenize::MacroHistory& history) {
  std::vector<double> state(static_cast<std::size_t>(law.stateSize()));
  law.initState(state.data());
  materials::PointStep step;
  materials::Vector6 sigma;
  materials::ReducedOrderStepInfo info;
  double t = 0, updates = 0;
  for (const homogenize::MacroStep& s : history.steps) {
    advance(step, s, t);
    law.updateWithInfo(step, state.data(), state.data(), sigma, nullptr, &info);
    updates += (info.iterations + 1) * static_cast<double>(law.nonlinearPartitions().size());
  }
  return updates / static_cast<double>(history.steps.size());
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    out.push_back(item);
  return out;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: %s LIBRARY ENTRY[,ENTRY...] CELL [N [THREADS [PATH [RATE [TO "
                 "[STEPS [MIN_SECONDS]]]]]]]\n",
                 argv[0]);
    return 2;
  }
  const std::string library = argv[1], cell_path = argv[3];
  const int n = argc > 4 ? std::atoi(argv[4]) : 32;
  const int threads = argc > 5 ? std::atoi(argv[5]) : 1;
  const auto path = materials::kDrivePathNames.parse(argc > 6 ? argv[6] : "confined");
  const double rate = argc > 7 ? std::atof(argv[7]) : 2.6e3;
  const double to = argc > 8 ? std::atof(argv[8]) : 0.3;
  const int steps = argc > 9 ? std::atoi(argv[9]) : 60;
  const double min_seconds = argc > 10 ? std::atof(argv[10]) : 2.0;
  materials::ReducedOrderOptions rom_options;
  if (argc > 11)
    rom_options.tolerance = std::atof(argv[11]);
  if (!path || *path == materials::DrivePath::UniaxialStress) {
    std::fprintf(stderr, "PATH: uniaxial-strain, shear or confined (strain paths)\n");
    return 2;
  }
  const homogenize::MacroHistory history = homogenize::pathHistory(*path, rate, to, steps, false);
  std::printf("history: %s at %g /s to %g in %d steps (small strain)\n", materials::toString(*path),
              rate, to, steps);

  materials::MaterialSource source(library);
  std::vector<double> rom_step, rom_updates;
  for (const std::string& name : split(argv[2])) {
    const materials::LawPtr law = source.law(name, rom_options);
    double stress = 0;
    const double dt = lawStep(*law, history, min_seconds, stress);
    rom_step.push_back(dt);
    const auto* rom = dynamic_cast<const materials::ReducedOrderLaw*>(law.get());
    rom_updates.push_back(rom ? lawUpdatesPerStep(*rom, history) : 1.0);
    std::printf("reduced-order %-12s state %5d doubles: step %.3g us, %.1f law updates "
                "(final max|sigma| %.6g Pa)\n",
                name.c_str(), law->stateSize(), 1e6 * dt, rom_updates.back(), stress);
  }
  std::printf("reduced-order Newton tolerance %g\n", rom_options.tolerance);

  const micro::CellSpec spec = micro::readCell(cell_path, micro::lazyCatalog());
  const micro::UnitCell cell = micro::buildCell(spec, {n, n, n});
  homogenize::NonlinearOptions options;
  options.threads = threads;
  const std::vector<std::int32_t> phase = cell.phase.toVector();
  const std::vector<materials::LawPtr> laws = homogenize::phaseLaws(spec);
  homogenize::NonlinearHomogenizer full(homogenize::gridOf(cell), phase, laws, options);
  const auto t0 = std::chrono::steady_clock::now();
  const auto results = full.run(history);
  const double full_step = seconds(t0) / static_cast<double>(results.size());
  double nonlinear_voxels = 0, newton = 0;
  for (std::int32_t p : phase)
    nonlinear_voxels += laws[static_cast<std::size_t>(p)]->isLinear() ? 0 : 1;
  for (const homogenize::StepResult& r : results)
    newton += r.newton;
  newton /= static_cast<double>(results.size());
  const double full_updates = nonlinear_voxels * (newton + 1);
  std::printf("full field %d^3, %d thread(s): step %.4g s, %.3g law updates (%.0f nonlinear voxels "
              "x %.2f Newton iterations + 1) (final max|sigma| %.6g Pa)\n",
              n, threads, full_step, full_updates, nonlinear_voxels, newton,
              results.back().Sigma.cwiseAbs().maxCoeff());
  for (std::size_t k = 0; k < rom_step.size(); ++k)
    std::printf("full-field step / reduced-order step (%s): %.3g; law updates %.3g\n",
                split(argv[2])[k].c_str(), full_step / rom_step[k], full_updates / rom_updates[k]);
  return 0;
}
