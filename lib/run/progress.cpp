#include "run/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace dem {

Progress::Progress(std::string label, std::int64_t total_steps, bool quiet, double log_interval)
    : label_(std::move(label)), total_(total_steps), quiet_(quiet), tty_(isatty(fileno(stderr)) != 0),
      interval_(tty_ ? 0.5 : log_interval), start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(std::int64_t steps_done, double sim_time) {
  if (first_step_ < 0) first_step_ = steps_done;
  if (quiet_ || (steps_done & 63) != 0) return;  // check the clock only now and then
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() < interval_) return;
  last_ = now;
  print(steps_done, sim_time, false);
}

void Progress::finish(std::int64_t steps_done, double sim_time) {
  if (first_step_ < 0) first_step_ = steps_done;
  if (!quiet_) print(steps_done, sim_time, true);
}

void Progress::print(std::int64_t done, double sim_time, bool final) {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = wall > 0 ? (done - first_step_) / wall : 0;
  const double pct = total_ > 0 ? 100.0 * done / total_ : 100.0;
  const double eta = rate > 0 ? (total_ - done) / rate : 0;
  std::fprintf(stderr, "%s%s: t = %.6g s, step %lld/%lld (%.1f%%), %.3g steps/s, ETA %.0f s%s", tty_ ? "\r" : "",
               label_.c_str(), sim_time, static_cast<long long>(done), static_cast<long long>(total_), pct, rate, eta,
               (tty_ && !final) ? "\033[K" : "\n");
  std::fflush(stderr);
}

}  // namespace dem
