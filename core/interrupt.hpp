#pragma once
/// @file interrupt.hpp
/// @brief SIGINT / SIGTERM as a request to stop at the next safe point.
///
/// While an InterruptGuard lives, the first SIGINT or SIGTERM only records
/// the signal; the work polls interruptSignal() between steps, finishes the
/// current one, writes its outputs and throws Interrupted. A second signal
/// of the same kind ends the process at once (the default action), so a
/// run that does not react can still be stopped.

#include "core/error.hpp"

namespace lamina::core {

/// @return the signal received since the guard was installed (SIGINT,
/// SIGTERM), 0 if none
int interruptSignal();

/// Asks the work to stop at its next safe point as if @p signal had been
/// received (the Python module: a progress callback that raised). The
/// request lasts until the next InterruptGuard is installed.
void requestInterrupt(int signal);

/// Throws Interrupted(@p what) if a signal was received or an interrupt
/// requested: the poll of work that has nothing to write when it stops
/// (a cell's solves). Free when no InterruptGuard is installed (the
/// request is then never set by a signal).
void throwIfInterrupted(const std::string& what);

/// Installs the handlers for its lifetime and restores the previous ones.
class InterruptGuard {
public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

/// @return "SIGINT", "SIGTERM" or "signal N"
std::string signalName(int signal);

} // namespace lamina::core

namespace lamina {

/// Thrown after an interrupted run has written its outputs. Programs exit
/// with 128 + signal() (130 for SIGINT, 143 for SIGTERM), the shell's code.
class Interrupted : public Error {
public:
  /// @param signal the signal that asked to stop
  /// @param message what was written
  Interrupted(int signal, const std::string& message) : Error(message), signal_(signal) {}
  /// @return the signal number
  int signal() const { return signal_; }
  /// @return the exit code: 128 + signal
  int exitCode() const { return 128 + signal_; }

private:
  int signal_;
};

} // namespace lamina
