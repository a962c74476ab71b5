#include "membrane/run.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"
#include "core/interrupt.hpp"
#include "core/progress.hpp"
#include "membrane/io/checkpoint.hpp"
#include "membrane/io/output.hpp"
#include "membrane/loads/blast_pressure.hpp"
#include "membrane/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>

namespace lamina::membrane {

namespace {

/// One run: the method reads as set-up, then steps with outputs, then summary.
class MembraneRun {
public:
  MembraneRun(const Model& model, const RunOptions& options)
      : model_(model), opt_(options),
        extra_energy_(!model.springs.empty() || model.time.damping > 0) {}

  nlohmann::json run() {
    const auto start = std::chrono::steady_clock::now();
    if (opt_.restart && !std::filesystem::is_directory(opt_.out_dir))
      throw Error("no output folder to restart from", {opt_.out_dir.string(), 0, ""});
    Simulation sim(model_); // assemble K, M; build A; set up its solver
    const std::optional<Checkpoint> resumed = prepare(sim);
    const long steps = steps_;
    core::ProgressLine progress("steps", std::max(1L, steps), opt_.quiet);
    std::optional<DivergenceError> failure;
    if (!resumed)
      try { // the initial state too: a non-finite start is a divergence at step 0
        record(sim, true, true);
      } catch (const DivergenceError& e) {
        failure = e;
      }
    const auto step_start = std::chrono::steady_clock::now();
    int interrupted = 0; // SIGINT/SIGTERM: stop after this step, outputs as they are
    bool stopped = false;
    const long ce = model_.output.checkpoint_every;
    for (long s = sim.steps() + 1; more(s) && !failure && !interrupted && !stopped; ++s) {
      if (adaptive_ && static_cast<double>(s) > kMaxSteps)
        throw Error("the explicit step shrank with the law's stiffness so far that t_end needs "
                    "more than " +
                        core::formatShort(kMaxSteps) +
                        " steps (t = " + core::formatShort(sim.time()) +
                        " s, dt = " + core::formatShort(sim.integrator().timeStep()) + " s)",
                    {"", 0, "time.t_end"});
      try {
        sim.step();
        reached_end_ = endReached(sim);
        interrupted = core::interruptSignal();
        record(sim, fieldStep(s), energyStep(s));
      } catch (const DivergenceError& e) {
        failure = e;
        break;
      }
      stopped = s == opt_.stop_at_step;
      if (interrupted || stopped || (ce > 0 && s % ce == 0))
        writeCheckpoint(sim);
      progress.update(s, "t = " + core::formatShort(sim.time(), 4));
    }
    step_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start).count();
    if (failure && fields_)
      writeFields(sim); // last finite state
    if (failure)
      record(sim, false, false);
    progress.finish();
    closeOutputs();
    wall_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json summary = summarize(sim);
    if (failure)
      summary["diverged"] = failure->message();
    summary["interrupted"] = interrupted != 0;
    if (interrupted)
      summary["signal"] = core::signalName(interrupted);
    if (stopped && !interrupted)
      summary["stopped_at_step"] = sim.steps();
    core::writeFileAtomically(opt_.out_dir / "summary.json", summary.dump(2) + "\n");
    if (failure)
      throw *failure;
    if (interrupted) {
      const auto& again = opt_.restart_folder.empty() ? opt_.out_dir : opt_.restart_folder;
      throw Interrupted(interrupted, "interrupted by " + core::signalName(interrupted) +
                                         " at t = " + core::formatShort(sim.time()) + " s (step " +
                                         std::to_string(sim.steps()) + " of " +
                                         std::to_string(steps) + "); outputs and checkpoint " +
                                         "written to " + opt_.out_dir.string() +
                                         " (continue with --restart " + again.string() + ")");
    }
    return summary;
  }

private:
  /// Before the steps: the number of steps, the checkpoint read and
  /// restored (a restart), the --stop-at-step checked, the output folder
  /// swept of debris and the outputs opened; @return the checkpoint (restart).
  std::optional<Checkpoint> prepare(Simulation& sim) {
    const double dt = sim.integrator().timeStep();
    if (!(model_.time.t_end / dt <= kMaxSteps)) // the explicit stable step may be tiny
      throw Error("t_end / dt = " + core::formatShort(model_.time.t_end / dt) + " steps; at most " +
                      core::formatShort(kMaxSteps),
                  {"", 0, "time.dt"});
    // Newmark: t_end is a multiple of dt by the case; explicit: cover t_end.
    steps_ = model_.time.integrator == IntegratorKind::Newmark
                 ? std::lround(model_.time.t_end / dt)
                 : static_cast<long>(std::ceil(model_.time.t_end / dt - 1e-9));
    // The explicit step of a structure whose stiffness follows the state (a
    // stretched fabric, a law with history) changes as the run goes
    // (Simulation::adaptStep): the run ends at t_end, steps_ is an estimate.
    adaptive_ =
        model_.time.integrator == IntegratorKind::Explicit && sim.structure().stateDependentStep();
    std::optional<Checkpoint> resumed;
    if (opt_.restart)
      resumed = resume(sim);
    reached_end_ = endReached(sim);
    const long stop = opt_.stop_at_step;
    const bool past = stop <= sim.steps() && !opt_.stop_may_be_past;
    if (stop > 0 && (past || (!adaptive_ && stop > steps_))) // never stops there
      throw Error("--stop-at-step " + std::to_string(stop) + " is not one of the steps " +
                      std::to_string(sim.steps() + 1) + " to " + std::to_string(steps_) +
                      " this run takes",
                  {"", 0, "--stop-at-step"});
    warnOnUnresolvedPulses(sim.integrator().timeStep());
    std::filesystem::create_directories(opt_.out_dir);
    // Debris of a run killed while replacing one of its files (the stage
    // files: the .part tables are rewritten or cut back by the CsvWriter).
    removeTemporaries(opt_.out_dir, {model_.name + ".xdmf", "summary.json",
                                     checkpointPath(opt_.out_dir).filename().string()});
    openOutputs(sim, resumed.has_value());
    return resumed;
  }

  /// The element fields of the current state (with the failure map).
  std::vector<CellField> fieldCells(const Simulation& sim) const {
    auto cells = sim.structure().cellFields(sim.u());
    if (sim.structure().hasFailureThresholds()) {
      const auto& f = sim.failure();
      CellField map{"failure_time", 1, f.time};
      map.values.resize(static_cast<size_t>(model_.mesh.numElements()), -1.0);
      cells.push_back(std::move(map));
    }
    return cells;
  }

  void writeFields(const Simulation& sim) {
    fields_->write(sim.time(), sim.u(), sim.v(), fieldCells(sim));
  }

  /// Opens the outputs: new ones, or (@p resumed: after resume()) those
  /// of the interrupted run, cut back to the checkpoint's step.
  void openOutputs(const Simulation& sim, bool resumed) {
    // Rows of each table at the checkpoint's step k: probes and reactions
    // one per step and the initial state, energies as energyStep() says.
    const long k = sim.steps();
    const std::uintmax_t rows[3] = {std::uintmax_t(k) + 1,
                                    std::uintmax_t(recordsUpTo(k, model_.output.energy_every)),
                                    std::uintmax_t(k) + 1};
    auto table = [&](const char* file, const std::string& header, int t) {
      if (!resumed)
        return std::make_unique<CsvWriter>(opt_.out_dir / file, header);
      try {
        return std::make_unique<CsvWriter>(opt_.out_dir / file, header, resumed_bytes_[t], rows[t]);
      } catch (const Error& e) {
        throw resumedOutputError(e, "run/csv_bytes", k);
      }
    };
    if (model_.output.fields) {
      const bool deformed = sim.structure().deformedGeometry();
      if (!resumed)
        fields_ = std::make_unique<FieldWriter>(opt_.out_dir, model_.name, model_.mesh, deformed);
      else
        try {
          fields_ = std::make_unique<FieldWriter>(opt_.out_dir, model_.name, model_.mesh, deformed,
                                                  resumed_field_times_, fieldCells(sim));
        } catch (const Error& e) {
          throw resumedOutputError(e, "run/field_times", k);
        }
    }
    std::string h = "t";
    for (const auto& p : model_.probes)
      for (const char* c : {"_ux", "_uy", "_uz", "_vx", "_vy", "_vz"})
        h += "," + p.name + c;
    probes_ = table("probes.csv", h, 0);
    energy_ =
        table("energy.csv",
              "t,kinetic,strain,external_work,reaction_work,drag_work,total,balance,"
              "micro_kinetic" +
                  std::string(extra_energy_ ? ",spring_work,damping_work" : "") +
                  std::string(sim.structure().nonConservativeWrinkling() ? ",wrinkling_dissipation"
                                                                         : "") +
                  std::string(sim.structure().hasHistory() ? ",inelastic_dissipation" : "") +
                  std::string(model_.contact.empty() ? "" : ",contact_work"),
              1);
    const auto names = sim.reactionNames();
    if (!names.empty()) {
      std::string r = "t";
      for (const auto& c : names)
        for (const char* k : {"_Rx", "_Ry", "_Rz"})
          r += "," + c + k;
      reactions_ = table("reactions.csv", r, 2);
    }
    if (!resumed) {
      peak_reaction_.assign(names.size(), 0.0);
      probe_peak_.assign(model_.probes.size(), 0.0);
    }
  }

  /// @return error @p e of continuing an output (naming it) that also names
  /// the checkpoint's entry @p key and step @p k it was continued from
  Error resumedOutputError(const Error& e, const std::string& key, long k) const {
    return Error(std::string(e.what()) + " (entry '" + key + "' of " +
                 checkpointPath(opt_.out_dir).string() + ", step " + std::to_string(k) + ")");
  }

  /// @return whether a step of an adaptive run (adaptive_) has reached t_end:
  /// as the fixed-step explicit run, which covers t_end by ceil(t_end / dt - 1e-9) steps
  bool endReached(const Simulation& sim) const {
    return adaptive_ && sim.time() >= model_.time.t_end - 1e-9 * sim.integrator().timeStep();
  }
  /// @return whether step @p s is still to be taken
  bool more(long s) const { return adaptive_ ? !reached_end_ : s <= steps_; }
  /// @return whether step @p s is the last (for step sim.steps() of an adaptive run)
  bool last(long s) const { return adaptive_ ? reached_end_ : s == steps_; }
  /// @return whether step @p s (of steps_) records the energies (the last always)
  bool energyStep(long s) const { return last(s) || s % model_.output.energy_every == 0; }
  /// @return whether step @p s (of steps_) writes the fields (the last always)
  bool fieldStep(long s) const {
    const int fe = model_.output.field_every;
    return last(s) || (fe > 0 && s % fe == 0);
  }
  /// @return the records up to step @p k (the initial one included) of an
  /// output written every @p every steps (0: the initial and the last only)
  /// and at the last step
  long recordsUpTo(long k, int every) const {
    const long regular = every > 0 ? k / every : 0;
    return 1 + regular + (last(k) && !(every > 0 && k % every == 0) ? 1 : 0);
  }

  /// The field times of checkpoint @p h, which must be those of the steps
  /// fieldStep() chose up to the checkpoint's step, exactly (t = s * dt);
  /// none without fields.
  std::vector<double> resumedFieldTimes(const History& h, const Simulation& sim) const {
    const int fe = model_.output.field_every;
    const long count = model_.output.fields ? recordsUpTo(sim.steps(), fe) : 0;
    const Eigen::VectorXd& times = historyEntry(h, "run/field_times", count);
    const double dt = sim.integrator().timeStep();
    if (adaptive_) { // the steps of the past are not kept: times in order, up to now
      for (Eigen::Index j = 0; j < times.size(); ++j)
        if (!(times[j] >= (j ? times[j - 1] : 0.0) && times[j] <= sim.time()))
          throw Error("checkpoint entry 'run/field_times' value " + std::to_string(j) + " is " +
                      core::formatExact(times[j]) +
                      " s, not in order up to t = " + core::formatExact(sim.time()) + " s");
      return {times.data(), times.data() + times.size()};
    }
    for (Eigen::Index j = 0; j < times.size(); ++j) {
      const long s = j + 1 == count && fieldStep(sim.steps()) ? sim.steps() : j * fe;
      if (times[j] != static_cast<double>(s) * dt)
        throw Error("checkpoint entry 'run/field_times' value " + std::to_string(j) + " is " +
                    core::formatExact(times[j]) + " s, field step " + std::to_string(s) +
                    " is at " + core::formatExact(static_cast<double>(s) * dt) + " s");
    }
    return {times.data(), times.data() + times.size()};
  }

  /// The run's bookkeeping as a History: running maxima, the last energy
  /// record, the bytes of each table and the times of the field series.
  History bookkeeping() const {
    History h;
    h["run/maxima"] = (Eigen::VectorXd(6) << max_abs_w_, max_speed_, max_balance_, energy_scale_,
                       max_disp_, peak_total_reaction_)
                          .finished();
    h["run/peak_support_reaction"] = Eigen::VectorXd::Constant(1, peak_support_reaction_);
    h["run/peak_reaction"] = Eigen::Map<const Eigen::VectorXd>(
        peak_reaction_.data(), static_cast<Eigen::Index>(peak_reaction_.size()));
    h["run/probe_peak"] = Eigen::Map<const Eigen::VectorXd>(
        probe_peak_.data(), static_cast<Eigen::Index>(probe_peak_.size()));
    const auto& e = last_energy_;
    h["run/last_energy"] =
        (Eigen::VectorXd(11) << e.kinetic, e.micro_kinetic, e.strain, e.external_work,
         e.reaction_work, e.drag_work, e.spring_work, e.damping_work, e.balance,
         e.wrinkling_dissipation, e.inelastic_dissipation)
            .finished();
    h["run/csv_bytes"] = Eigen::Vector3d(static_cast<double>(probes_->bytes()),
                                         static_cast<double>(energy_->bytes()),
                                         reactions_ ? static_cast<double>(reactions_->bytes()) : 0);
    // OpenMP threads: a sum split over another number of threads rounds
    // differently, so a restart compares it (warning only).
    h["run/omp_threads"] = Eigen::VectorXd::Constant(1, omp_get_max_threads());
    std::vector<double> times;
    if (fields_)
      times = fields_->times();
    h["run/field_times"] =
        Eigen::Map<const Eigen::VectorXd>(times.data(), static_cast<Eigen::Index>(times.size()));
    if (!model_.contact.empty())
      h["run/last_contact_work"] = Eigen::VectorXd::Constant(1, e.contact_work);
    return h;
  }

  /// Writes out_dir/checkpoint.h5: the simulation's history and the run's bookkeeping.
  void writeCheckpoint(const Simulation& sim) const {
    Checkpoint c{model_.name, digest(), bookkeeping()};
    sim.save(c.data);
    membrane::writeCheckpoint(checkpointPath(opt_.out_dir), c);
  }

  /// Reads out_dir/checkpoint.h5, checks it is this case's, restores @p sim
  /// and the bookkeeping; @return the checkpoint.
  Checkpoint resume(Simulation& sim) {
    const auto path = checkpointPath(opt_.out_dir);
    Checkpoint c = readCheckpoint(path);
    const ErrorContext where{path.string(), 0, ""};
    // A checkpoint is input: every count, size and value below is checked
    // against this run (the checksum only tells that the file is whole).
    if (c.case_digest != digest())
      throw Error("checkpoint belongs to another case ('" + c.case_name + "', digest " +
                      c.case_digest + "; this case '" + model_.name + "' has digest " + digest() +
                      "): restart with the case file and --set options of the interrupted run",
                  where);
    try {
      sim.restore(c.data, adaptive_ ? static_cast<long>(kMaxSteps) : steps_);
      reached_end_ = endReached(sim); // the field and energy counts below need it
      const auto& h = c.data;
      for (const char* key : {"run/maxima", "run/peak_reaction", "run/probe_peak"})
        if (const auto it = h.find(key); it != h.end() && (it->second.array() < 0).any())
          throw Error(std::string("checkpoint entry '") + key + "' holds a negative maximum");
      if (h.count("run/omp_threads")) // absent from checkpoints written before it was recorded
        historyInteger(h, "run/omp_threads", 1, 0, 1, std::numeric_limits<int>::max());
      const Eigen::VectorXd& m = historyEntry(h, "run/maxima", 6);
      max_abs_w_ = m[0];
      max_speed_ = m[1];
      max_balance_ = m[2];
      energy_scale_ = m[3];
      max_disp_ = m[4];
      peak_total_reaction_ = m[5];
      if (h.count("run/peak_support_reaction")) // absent from checkpoints before it was kept
        peak_support_reaction_ = historyEntry(h, "run/peak_support_reaction", 1)[0];
      const auto nr = static_cast<Eigen::Index>(sim.reactionNames().size());
      const Eigen::VectorXd& pr = historyEntry(h, "run/peak_reaction", nr);
      peak_reaction_.assign(pr.data(), pr.data() + nr);
      const auto np = static_cast<Eigen::Index>(model_.probes.size());
      const Eigen::VectorXd& pp = historyEntry(h, "run/probe_peak", np);
      probe_peak_.assign(pp.data(), pp.data() + np);
      const Eigen::VectorXd& e = historyEntry(h, "run/last_energy", 11);
      last_energy_ = Energy{e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], e[8], e[9], e[10]};
      if (!model_.contact.empty())
        last_energy_.contact_work = historyEntry(h, "run/last_contact_work", 1)[0];
      constexpr long kMaxBytes = 1L << 53; // doubles hold every integer up to here
      for (int t = 0; t < 3; ++t)
        resumed_bytes_[t] =
            static_cast<std::uintmax_t>(historyInteger(h, "run/csv_bytes", 3, t, 0, kMaxBytes));
      resumed_field_times_ = resumedFieldTimes(h, sim);
      warnOnOtherThreadCount(c.data, path);
    } catch (const Error& e) {
      throw Error("checkpoint does not fit this run: " + e.message(), where);
    }
    return c;
  }

  /// Warns (stderr) when the step @p dt is longer than a blast's positive
  /// phase: the steps still receive the pulse's impulse (each the mean over
  /// its interval), but neither its shape nor its work is resolved.
  void warnOnUnresolvedPulses(double dt) const {
    for (const auto& load : model_.surface_loads)
      if (const auto* blast = dynamic_cast<const BlastPressure*>(load.get()))
        if (const double phase = blast->shortestPhase(); dt > phase)
          std::cerr << "warning: [[blast]] '" << blast->name() << "': the time step "
                    << core::formatShort(dt) << " s is longer than its positive phase "
                    << core::formatShort(phase)
                    << " s: each step receives the pulse's impulse, but neither its shape nor "
                       "the work it does is resolved (lower time.dt or time.safety)\n";
  }

  /// Warns (stderr) when checkpoint @p h was written with another number
  /// of OpenMP threads than this run has: the run continues, but its
  /// results may differ from an uninterrupted run in the last bits.
  static void warnOnOtherThreadCount(const History& h, const std::filesystem::path& path) {
    const auto it = h.find("run/omp_threads");
    if (it == h.end() || it->second.size() != 1) // a checkpoint written before it was recorded
      return;
    const int then = static_cast<int>(it->second[0]), now = omp_get_max_threads();
    if (then != now)
      std::cerr << "warning: " << path.string() << " was written with " << then
                << " OpenMP threads, this run has " << now
                << " (OMP_NUM_THREADS): the continued run is not guaranteed to be bit-identical "
                   "to an uninterrupted one; restart with OMP_NUM_THREADS="
                << then << " for that\n";
  }

  std::string digest() const { return opt_.case_digest.empty() ? model_.name : opt_.case_digest; }

  /// A row of reactions.csv at the current state and the running peaks of
  /// each set, of their sum and of the supports' sum (without the rigid surfaces).
  void recordReactions(const Simulation& sim) {
    const auto sums = sim.reactionSums();
    std::vector<double> r{sim.time()};
    Eigen::Vector3d total = Eigen::Vector3d::Zero(), supports = Eigen::Vector3d::Zero();
    // the rigid surfaces come last (Simulation::reactionSums)
    const size_t n_supports = sums.size() - std::min(sums.size(), model_.contact.size());
    for (size_t k = 0; k < sums.size(); ++k) {
      for (int c = 0; c < 3; ++c)
        r.push_back(sums[k][c]);
      peak_reaction_[k] = std::max(peak_reaction_[k], sums[k].norm());
      total += sums[k];
      if (k < n_supports)
        supports += sums[k];
    }
    peak_total_reaction_ = std::max(peak_total_reaction_, total.norm());
    peak_support_reaction_ = std::max(peak_support_reaction_, supports.norm());
    reactions_->row(r);
  }

  /// Folds the largest |w|, |u| and |v| over the nodes of @p u, @p v into
  /// the run's maxima, threaded over the nodes. The largest squared norm
  /// and one square root give the largest norm itself: Eigen's norm() is
  /// the square root of squaredNorm(), correctly rounded and monotonic.
  /// NaN is skipped as std::max skips it.
  void foldMaxima(const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    const int n = model_.mesh.numNodes();
    double w = 0, d2 = 0, s2 = 0;
#pragma omp parallel for schedule(static) reduction(max : w, d2, s2) if (n > kParallelDofs / 3)
    for (int i = 0; i < n; ++i) {
      w = std::max(w, std::abs(u[3 * i + 2]));
      d2 = std::max(d2, u.segment<3>(3 * i).squaredNorm());
      s2 = std::max(s2, v.segment<3>(3 * i).squaredNorm());
    }
    max_abs_w_ = std::max(max_abs_w_, w);
    max_disp_ = std::max(max_disp_, std::sqrt(d2));
    max_speed_ = std::max(max_speed_, std::sqrt(s2));
  }

  void record(const Simulation& sim, bool fields, bool energy) {
    const auto& u = sim.u();
    const auto& v = sim.v();
    const int n = model_.mesh.numNodes();
    foldMaxima(u, v);
    std::vector<double> row{sim.time()};
    for (size_t k = 0; k < model_.probes.size(); ++k) {
      const int i = model_.probes[k].node;
      for (int c = 0; c < 3; ++c)
        row.push_back(u[3 * i + c]);
      for (int c = 0; c < 3; ++c)
        row.push_back(v[3 * i + c]);
      probe_peak_[k] = std::max(probe_peak_[k], std::abs(u[3 * i + 2]));
    }
    probes_->row(row);
    if (reactions_)
      recordReactions(sim);
    if (energy) {
      last_energy_ = sim.energy();
      if (!std::isfinite(last_energy_.kinetic + last_energy_.strain + last_energy_.reaction_work)) {
        int worst = 0;
        double big = -1;
        for (int i = 0; i < n; ++i) {
          const double s = u.segment<3>(3 * i).norm() + v.segment<3>(3 * i).norm();
          if (!(s <= big)) {
            big = s;
            worst = i;
          }
        }
        const auto& p = model_.mesh.nodes[worst];
        throw DivergenceError("non-finite energy at t = " + core::formatShort(sim.time()) +
                              " s (step " + std::to_string(sim.steps()) +
                              "), largest motion at node " +
                              std::to_string(model_.mesh.nodeLabel(worst)) + " (" +
                              core::formatShort(p.x()) + ", " + core::formatShort(p.y()) + ")");
      }
      const auto& e = last_energy_;
      const double total = e.kinetic + e.strain;
      max_balance_ = std::max(max_balance_, std::abs(e.balance));
      energy_scale_ = std::max({energy_scale_, total, std::abs(e.external_work),
                                std::abs(e.reaction_work), std::abs(e.drag_work)});
      std::vector<double> row{sim.time(),  e.kinetic, e.strain,  e.external_work, e.reaction_work,
                              e.drag_work, total,     e.balance, e.micro_kinetic};
      if (extra_energy_) {
        row.push_back(e.spring_work);
        row.push_back(e.damping_work);
      }
      if (sim.structure().nonConservativeWrinkling())
        row.push_back(e.wrinkling_dissipation);
      if (sim.structure().hasHistory())
        row.push_back(e.inelastic_dissipation);
      if (!model_.contact.empty())
        row.push_back(e.contact_work);
      energy_->row(row);
      energy_scale_ = std::max({energy_scale_, std::abs(e.spring_work), std::abs(e.damping_work),
                                std::abs(e.wrinkling_dissipation), e.inelastic_dissipation,
                                std::abs(e.contact_work)});
    }
    if (fields && fields_)
      writeFields(sim);
  }

  void closeOutputs() {
    probes_->close();
    energy_->close();
    if (reactions_)
      reactions_->close();
  }

  nlohmann::json summarize(const Simulation& sim) const {
    nlohmann::json s;
    s["case"] = model_.name;
    s["nodes"] = model_.mesh.numNodes();
    s["elements"] = model_.mesh.numElements();
    s["dofs"] = model_.numDofs();
    s["steps"] = sim.steps();
    s["dt"] = sim.integrator().timeStep();
    s["t_end"] = sim.time();
    s["max_abs_w"] = max_abs_w_;
    s["max_speed"] = max_speed_;
    const auto& e = last_energy_;
    s["energy"] = {{"initial", sim.initialEnergy()},
                   {"kinetic", e.kinetic},
                   {"micro_kinetic", e.micro_kinetic},
                   {"strain", e.strain},
                   {"external_work", e.external_work},
                   {"reaction_work", e.reaction_work},
                   {"drag_work", e.drag_work},
                   {"balance", e.balance},
                   {"spring_work", e.spring_work},
                   {"damping_work", e.damping_work},
                   {"max_abs_balance", max_balance_},
                   {"relative_balance", energy_scale_ > 0 ? max_balance_ / energy_scale_ : 0.0}};
    if (sim.structure().nonConservativeWrinkling())
      s["energy"]["wrinkling_dissipation"] = e.wrinkling_dissipation;
    if (sim.structure().hasHistory())
      s["energy"]["inelastic_dissipation"] = e.inelastic_dissipation;
    if (!model_.contact.empty()) {
      s["energy"]["contact_work"] = e.contact_work;
      s["contact"] = contactSummary(sim);
    }
    nlohmann::json probes = nlohmann::json::object();
    for (size_t k = 0; k < model_.probes.size(); ++k) {
      const auto& p = model_.probes[k];
      const int i = p.node;
      probes[p.name] = {{"node", model_.mesh.nodeLabel(i)},
                        {"x", model_.mesh.nodes[i].x()},
                        {"y", model_.mesh.nodes[i].y()},
                        {"u", {sim.u()[3 * i], sim.u()[3 * i + 1], sim.u()[3 * i + 2]}},
                        {"v", {sim.v()[3 * i], sim.v()[3 * i + 1], sim.v()[3 * i + 2]}},
                        {"max_abs_uz", probe_peak_[k]}};
    }
    s["probes"] = probes;
    nlohmann::json reac = nlohmann::json::object();
    const auto sums = sim.reactionSums();
    const auto names = sim.reactionNames();
    for (size_t k = 0; k < names.size(); ++k)
      reac[names[k]] = {{"peak", peak_reaction_[k]},
                        {"final", {sums[k][0], sums[k][1], sums[k][2]}}};
    s["reactions"] = reac;
    s["peak_reaction_total"] = peak_total_reaction_;
    s["peak_reaction_supports"] = peak_support_reaction_;
    s["max_displacement"] = max_disp_;
    s["model"] = std::string(kModelKindNames.name(model_.kind));
    s["integrator"] = {{"name", sim.integrator().name()}, {"stable_dt", sim.stableStep()}};
    if (model_.time.integrator == IntegratorKind::Explicit)
      s["integrator"]["safety"] = sim.integrator().timeStep() / sim.stableStep();
    if (sim.structure().hasFailureThresholds()) {
      const auto& f = sim.failure();
      s["failure"] =
          f.first_element < 0
              ? nlohmann::json{{"element", nullptr}}
              : nlohmann::json{
                    {"element", model_.mesh.elementLabel(f.first_element)},
                    {"time", f.first_time},
                    {"criterion", failureName(f.first_criterion)},
                    {"region", model_.mesh.regions[model_.mesh.region_of[f.first_element]]}};
    }
    const SolverStats st = sim.integrator().stats();
    s["solver"] = {
        {"type", std::string(kLinearSolverKindNames.name(model_.time.solver))},
        {"mean_iterations", st.solves ? double(st.iterations) / double(st.solves) : 0.0}};
    s["wall_s"] = wall_s_;
    s["assembly_s"] = sim.assemblySeconds();
    s["factor_s"] = sim.setupSeconds();
    s["step_s"] = sim.steps() ? step_s_ / double(sim.steps()) : 0.0;
    return s;
  }

  /// The summary's "contact": per rigid surface its deepest penetration
  /// (when, where, against its tolerance), its peak and final force on the
  /// membrane (the reactions' entry) and, for a free body, its motion.
  nlohmann::json contactSummary(const Simulation& sim) const {
    nlohmann::json c = nlohmann::json::object();
    const auto names = sim.reactionNames();
    const auto sums = sim.reactionSums();
    const size_t first = names.size() - model_.contact.size();
    for (size_t k = 0; k < model_.contact.size(); ++k) {
      const ContactSurface& cs = model_.contact[k];
      const PenetrationPeak& p = sim.penetration()[k];
      const Eigen::Vector3d& f = sums[first + k];
      nlohmann::json j = {
          {"shape", std::string(kSurfaceShapeNames.name(cs.geometry.shape))},
          {"max_penetration", p.depth},
          {"penetration_tolerance", cs.tolerance},
          {"max_penetration_time", p.time},
          {"max_penetration_node",
           p.node < 0 ? nlohmann::json(nullptr) : nlohmann::json(model_.mesh.nodeLabel(p.node))},
          {"peak_force", peak_reaction_[first + k]},
          {"final_force", {f[0], f[1], f[2]}}};
      if (cs.free()) {
        const auto at = static_cast<Eigen::Index>(3 * k);
        const Eigen::Vector3d d = sim.state().surfaces.u.segment<3>(at);
        const Eigen::Vector3d v = sim.state().surfaces.v.segment<3>(at);
        j["displacement"] = {d[0], d[1], d[2]};
        j["velocity"] = {v[0], v[1], v[2]};
        j["kinetic_energy"] = 0.5 * cs.mass * v.squaredNorm();
      }
      c[cs.name] = j;
    }
    return c;
  }

  const Model& model_;
  RunOptions opt_;
  bool extra_energy_; // spring and damping columns in energy.csv
  std::unique_ptr<FieldWriter> fields_;
  std::unique_ptr<CsvWriter> probes_, energy_, reactions_;
  std::vector<double> peak_reaction_, probe_peak_;
  long steps_ = 0;           // steps of the whole run (adaptive: estimate)
  bool adaptive_ = false;    // the explicit step follows a law's state: the run ends at t_end
  bool reached_end_ = false; // adaptive_: the current state is at t_end
  std::uintmax_t resumed_bytes_[3] = {0, 0, 0}; // a checkpoint's table sizes
  std::vector<double> resumed_field_times_;     // and field times
  Energy last_energy_;
  double max_abs_w_ = 0, max_speed_ = 0, max_balance_ = 0, energy_scale_ = 0;
  double max_disp_ = 0, peak_total_reaction_ = 0;
  double peak_support_reaction_ = 0; ///< peak |sum| of the constraints' and springs' reactions
  double wall_s_ = 0, step_s_ = 0;
};

/// A compare_without_drag case: the run with drag, then the run without, each
/// in its own folder with its own checkpoint (runCase() says what a stop and
/// a restart do).
class DragComparison {
public:
  DragComparison(const Model& model, const RunOptions& options)
      : model_(model), top_(options.out_dir), with_(options), without_(options) {
    with_.out_dir = top_ / "with-drag";
    without_.out_dir = top_ / "without-drag";
    with_.restart_folder = without_.restart_folder = top_;
    // Another digest: a checkpoint of one run is refused by the other.
    without_.case_digest =
        (options.case_digest.empty() ? model.name : options.case_digest) + "/without-drag";
  }

  nlohmann::json run() {
    if (with_.restart)
      checkRestartFolder();
    removeTemporaries(top_, {"summary.json"}); // as runModel() does in its folder
    std::optional<nlohmann::json> first;
    if (with_.restart)
      first = endedRun(with_.out_dir);
    if (first) { // the run with drag has ended: continue the one without
      without_.restart = true;
    } else { // continue (or start) the run with drag; the one without starts afresh
      with_.stop_may_be_past = true; // a step it is past is the second run's stop
      first = runOne(model_, with_);
      if (first->contains("stopped_at_step"))
        return stopped(*first, with_);
      without_.restart = false;
    }
    const nlohmann::json second = runOne(bareModel(), without_);
    if (second.contains("stopped_at_step"))
      return stopped(second, without_);
    nlohmann::json summary = *first;
    summary["drag_comparison"] = {{"with_drag", peaks(*first)}, {"without_drag", peaks(second)}};
    core::writeFileAtomically(top_ / "summary.json", summary.dump(2) + "\n");
    return summary;
  }

private:
  /// Refuses a restart from a missing folder, or from the folder of one of
  /// the two runs (the case's folder holds both).
  void checkRestartFolder() const {
    if (!std::filesystem::is_directory(top_))
      throw Error("no output folder to restart from", {top_.string(), 0, ""});
    auto dir = top_.lexically_normal();
    if (!dir.has_filename()) // "DIR/"
      dir = dir.parent_path();
    const auto name = dir.filename().string();
    if ((name == "with-drag" || name == "without-drag") &&
        !std::filesystem::is_directory(with_.out_dir))
      throw Error("this is the folder of one of the two runs of a compare_without_drag case; "
                  "restart with the case's folder " +
                      (dir.has_parent_path() ? dir.parent_path() : ".").string(),
                  {top_.string(), 0, "--restart"});
  }

  /// @return the summary of the run in @p dir when it ended (its
  /// summary.json records no interrupt, stop or divergence, and no table is
  /// still a .part file), else none (a run to continue from its checkpoint)
  static std::optional<nlohmann::json> endedRun(const std::filesystem::path& dir) {
    for (const char* table : {"probes.csv.part", "energy.csv.part", "reactions.csv.part"})
      if (std::filesystem::exists(dir / table))
        return std::nullopt; // killed mid-run: its summary.json is an older run's
    const std::optional<nlohmann::json> s = readSummary(dir);
    if (!s || !s->is_object() || s->value("interrupted", false) || s->contains("stopped_at_step") ||
        s->contains("diverged"))
      return std::nullopt;
    return s;
  }

  /// @return DIR/summary.json of @p dir, none when missing or unreadable
  static std::optional<nlohmann::json> readSummary(const std::filesystem::path& dir) {
    const auto path = dir / "summary.json";
    if (!std::filesystem::exists(path))
      return std::nullopt;
    try {
      auto s = nlohmann::json::parse(core::readWholeFile(path, core::kMaxTableBytes, "summary"),
                                     nullptr, false);
      if (!s.is_discarded())
        return s;
    } catch (const Error&) {
    }
    return std::nullopt;
  }

  /// runModel(@p model, @p o); a signal or a divergence (summary.json
  /// written, then rethrown) ends the case as stopped() does.
  nlohmann::json runOne(const Model& model, const RunOptions& o) const {
    try {
      return runModel(model, o);
    } catch (const Interrupted&) {
      if (const auto s = readSummary(o.out_dir))
        stopped(*s, o);
      throw;
    } catch (const DivergenceError&) {
      if (const auto s = readSummary(o.out_dir))
        stopped(*s, o);
      throw;
    }
  }

  /// Writes and @return the case's summary.json of a case stopped in the
  /// run of @p o: that run's summary @p s and "stopped_run" (its folder).
  nlohmann::json stopped(nlohmann::json s, const RunOptions& o) const {
    s["stopped_run"] = o.out_dir.filename().string();
    core::writeFileAtomically(top_ / "summary.json", s.dump(2) + "\n");
    return s;
  }

  /// @return the case without its drag tables and drag loads
  Model bareModel() const {
    Model bare = model_;
    bare.surface_loads.erase(
        std::remove_if(bare.surface_loads.begin(), bare.surface_loads.end(),
                       [](const auto& l) { return l->kind() == WorkKind::Drag; }),
        bare.surface_loads.end());
    bare.compare_without_drag = false;
    return bare;
  }

  /// @return what drag_comparison compares of one run's summary @p s
  static nlohmann::json peaks(const nlohmann::json& s) {
    double reaction = 0;
    for (const auto& [name, r] : s["reactions"].items())
      reaction = std::max(reaction, r["peak"].get<double>());
    return nlohmann::json{{"max_abs_w", s["max_abs_w"]},
                          {"max_speed", s["max_speed"]},
                          {"peak_reaction", reaction},
                          {"peak_total_reaction", s["peak_reaction_total"]},
                          {"peak_support_reaction", s["peak_reaction_supports"]},
                          {"reactions", s["reactions"]}};
  }

  const Model& model_;
  std::filesystem::path top_; // the case's folder
  RunOptions with_, without_; // the two runs'
};

} // namespace

nlohmann::json runModel(const Model& model, const RunOptions& options) {
  return MembraneRun(model, options).run();
}

nlohmann::json runCase(const Model& model, const RunOptions& options) {
  if (!model.compare_without_drag)
    return runModel(model, options);
  return DragComparison(model, options).run();
}

} // namespace lamina::membrane
