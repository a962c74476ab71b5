#pragma once
/// @file progress.hpp
/// @brief Progress reporting for long work (time steps, solver iterations).
///
/// On a terminal (stderr is a tty) the line is redrawn in place; otherwise a
/// log line is written every @p log_every_percent percent. Quiet mode prints
/// nothing (used by --json runs and tests).

#include <chrono>
#include <functional>
#include <string>

namespace lamina::core {

/// What a progress observer receives: the line's label, the units done and
/// their total.
using ProgressObserver = std::function<void(const std::string& label, long done, long total)>;

/// Routes every ProgressLine of the calling thread to @p observer for its
/// lifetime (the Python module's progress callbacks), whether or not the
/// line prints. An observer sees at most one update per 0.2 s of a line, its
/// first and its last (done == total, or the finish). Scopes nest; the
/// previous observer is restored on destruction.
class ScopedProgressObserver {
public:
  /// @param observer called from the thread that reports progress
  explicit ScopedProgressObserver(ProgressObserver observer);
  ~ScopedProgressObserver();
  ScopedProgressObserver(const ScopedProgressObserver&) = delete;
  ScopedProgressObserver& operator=(const ScopedProgressObserver&) = delete;

private:
  ProgressObserver previous_;
};

/// One progress line on stderr.
class ProgressLine {
public:
  /// @param label what is progressing ("steps", "load case 3/6")
  /// @param total number of units of work (> 0)
  /// @param quiet print nothing at all
  /// @param log_every_percent spacing of log lines when stderr is not a tty
  ProgressLine(std::string label, long total, bool quiet = false, int log_every_percent = 10);
  /// Reports that @p done units are complete; @p note is appended (e.g. a residual).
  void update(long done, const std::string& note = "");
  /// Ends the line (prints a newline on a terminal).
  void finish(const std::string& note = "");

private:
  std::string label_;
  long total_;
  bool quiet_;
  bool tty_;
  int every_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_, last_observed_;
  bool observed_ = false; ///< the observer has seen this line

  /// Passes (done, total) to the thread's observer, if any, at most every 0.2 s
  void observe(long done, bool last);
};

} // namespace lamina::core
