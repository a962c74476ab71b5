#include "core/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace lamina::core {

namespace {
thread_local ProgressObserver t_observer;
} // namespace

ScopedProgressObserver::ScopedProgressObserver(ProgressObserver observer)
    : previous_(std::move(t_observer)) {
  t_observer = std::move(observer);
}

ScopedProgressObserver::~ScopedProgressObserver() {
  t_observer = std::move(previous_);
}

void ProgressLine::observe(long done, bool last) {
  if (!t_observer)
    return;
  const auto now = std::chrono::steady_clock::now();
  if (observed_ && !last && now - last_observed_ < std::chrono::milliseconds(200))
    return;
  observed_ = true;
  last_observed_ = now;
  t_observer(label_, done, total_);
}

ProgressLine::ProgressLine(std::string label, long total, bool quiet, int log_every_percent)
    : label_(std::move(label)), total_(std::max(1L, total)), quiet_(quiet),
      tty_(::isatty(STDERR_FILENO) != 0), every_(std::max(1, log_every_percent)),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

void ProgressLine::update(long done, const std::string& note) {
  observe(done, done >= total_);
  if (quiet_)
    return;
  const int percent = static_cast<int>(100.0 * static_cast<double>(done) / total_);
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (tty_) {
    if (now - last_draw_ < std::chrono::milliseconds(100) && done < total_)
      return;
    last_draw_ = now;
    std::fprintf(stderr, "\r%s %ld/%ld (%3d%%) %.1fs %s\033[K", label_.c_str(), done, total_,
                 percent, elapsed, note.c_str());
    std::fflush(stderr);
  } else if (percent / every_ > last_percent_ / every_ || last_percent_ < 0) {
    last_percent_ = percent;
    std::fprintf(stderr, "%s %ld/%ld (%d%%) %.1fs %s\n", label_.c_str(), done, total_, percent,
                 elapsed, note.c_str());
  }
}

void ProgressLine::finish(const std::string& note) {
  observe(total_, true);
  if (quiet_)
    return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (tty_)
    std::fprintf(stderr, "\r%s done in %.2fs %s\033[K\n", label_.c_str(), elapsed, note.c_str());
  else
    std::fprintf(stderr, "%s done in %.2fs %s\n", label_.c_str(), elapsed, note.c_str());
}

} // namespace lamina::core
