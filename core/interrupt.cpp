#include "core/interrupt.hpp"

#include <csignal>
#include <cstring>

namespace lamina::core {

namespace {
volatile std::sig_atomic_t g_signal = 0;
struct sigaction g_previous_int, g_previous_term;

extern "C" void onSignal(int sig) {
  if (g_signal == sig) { // asked twice: stop now, as without the guard
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_signal = sig;
}
} // namespace

int interruptSignal() {
  return static_cast<int>(g_signal);
}

void requestInterrupt(int signal) {
  g_signal = signal;
}

void throwIfInterrupted(const std::string& what) {
  if (const int sig = interruptSignal())
    throw Interrupted(sig, what + " stopped by " + signalName(sig));
}

InterruptGuard::InterruptGuard() {
  g_signal = 0;
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART; // reads and writes in progress carry on
  ::sigaction(SIGINT, &sa, &g_previous_int);
  ::sigaction(SIGTERM, &sa, &g_previous_term);
}

InterruptGuard::~InterruptGuard() {
  ::sigaction(SIGINT, &g_previous_int, nullptr);
  ::sigaction(SIGTERM, &g_previous_term, nullptr);
}

std::string signalName(int signal) {
  if (signal == SIGINT)
    return "SIGINT";
  if (signal == SIGTERM)
    return "SIGTERM";
  return "signal " + std::to_string(signal);
}

} // namespace lamina::core
