#include "common/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace flotsam {

Progress::Progress(std::string label, double total, double log_interval, bool quiet)
    : label_(std::move(label)),
      total_(total),
      log_interval_(log_interval),
      quiet_(quiet),
      tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void Progress::update(double sim_time, double dt, long steps) {
    if (quiet_) return;
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (since < (tty_ ? 0.25 : log_interval_)) return;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = double(steps - steps_at_last_) / since;
    const double eta = sim_time > 0 ? elapsed * (total_ - sim_time) / sim_time : 0.0;
    std::fprintf(stderr, "%s%s t=%8.2f/%.0f s  dt=%.2e s  %7.0f steps/s  ETA %5.0f s%s", tty_ ? "\r" : "", label_.c_str(), sim_time,
                 total_, dt, rate, eta, tty_ ? "\x1b[K" : "\n");
    std::fflush(stderr);
    last_ = now;
    steps_at_last_ = steps;
    printed_ = true;
}

void Progress::finish(double sim_time, long steps) {
    if (quiet_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "%s%s done: t=%.2f s, %ld steps in %.1f s wall%s\n", tty_ && printed_ ? "\r" : "", label_.c_str(),
                 sim_time, steps, elapsed, tty_ ? "\x1b[K" : "");
    std::fflush(stderr);
}

}  // namespace flotsam
