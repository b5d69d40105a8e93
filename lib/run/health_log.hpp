#pragma once
// The health log of run-stage (sim/health.hpp): every `every` steps and at the last step of the
// stage, one CSV row (OUT with .health.csv) and, unless quiet, one console line. Partial file and
// restart as the other series (io/csv_series.hpp): a resumed run keeps the rows up to its
// checkpoint's step and continues with the next, so the finished file equals an uninterrupted run's.
#include <cstdint>
#include <string>
#include <vector>

#include "core/interval.hpp"
#include "io/csv_series.hpp"
#include "run/wall_log.hpp"
#include "sim/health.hpp"
#include "sim/simulation.hpp"

namespace dem {

// The health log that belongs to an output path: "x.h5" -> "x.health.csv".
std::string health_path(const std::string& out);

// Steps between health rows: `cli` if given (run-stage --health-every), else the stage's
// health_every if given, else a hundredth of the stage but at least kMinDefaultEvery steps (a row
// costs about one step: bench/results/health.md).
constexpr std::int64_t kMinDefaultHealthEvery = 500;
std::int64_t health_interval(const Interval& cli, const Interval& scene, double stage_duration, double dt);

class HealthLog {
 public:
  // `start_bonds`: intact bonds when the stage began (broken = start_bonds - intact now; < 0 =
  // unknown, the column is left empty).
  HealthLog(const std::string& path, const std::vector<Wall>& walls, std::int64_t every, std::int64_t total_steps,
            std::int64_t resume_step, std::int64_t start_bonds, bool quiet);

  // A row (and a console line) if `steps_done` is a multiple of `every` or `last`.
  void record(const Simulation& sim, std::int64_t steps_done, bool last) {
    if (steps_done % every_ == 0 || last) write(sim, steps_done);
  }
  void finish() { csv_.finish(); }
  void discard() { csv_.discard(); }
  const std::string& last_line() const { return last_line_; }  // the console text of the last row, "" before one

 private:
  void write(const Simulation& sim, std::int64_t steps_done);
  CsvSeries csv_;
  std::int64_t every_, total_, start_bonds_;
  bool quiet_, tty_;
  WallGroups groups_;
  std::string last_line_;
};

}  // namespace dem
