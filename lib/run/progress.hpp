#pragma once
// Progress of a long run: a self-updating line on a terminal (stage time %, steps/s, ETA), plain
// log lines at most every `log_interval` seconds otherwise (e.g. under make or a batch system).
#include <chrono>
#include <cstdint>
#include <string>

namespace dem {

class Progress {
 public:
  Progress(std::string label, std::int64_t total_steps, bool quiet = false, double log_interval = 10.0);
  void update(std::int64_t steps_done, double sim_time);
  void finish(std::int64_t steps_done, double sim_time);

 private:
  void print(std::int64_t steps_done, double sim_time, bool final);
  std::string label_;
  std::int64_t total_;
  std::int64_t first_step_ = -1;
  bool quiet_, tty_;
  double interval_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace dem
