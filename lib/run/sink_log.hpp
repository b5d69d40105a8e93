#pragma once
// The produced-particles log of a stage with a [stage.sink] (generation/sink.hpp): OUT with
// .sink.csv, one row at the stage start, one after each sink event that removed particles, and
// one at the last step, each with the running totals. Partial file and restart as the other series
// (io/csv_series.hpp).
#include <cstdint>
#include <string>

#include "generation/sink.hpp"
#include "io/csv_series.hpp"
#include "sim/simulation.hpp"

namespace dem {

// The sink log that belongs to an output path: "x.h5" -> "x.sink.csv".
std::string sink_path(const std::string& out);

class SinkLog {
 public:
  // `path` empty: no log. `resume_step` >= 0: continue the partial file of an interrupted run.
  SinkLog(const std::string& path, std::int64_t resume_step);
  // A row of the totals after `removed` particles went at this step (a row when removed > 0 or
  // `force`: the stage start and end).
  void record(const Simulation& sim, const SinkTotals& totals, std::size_t removed, bool force);
  void finish() { csv_.finish(); }
  void discard() { csv_.discard(); }

 private:
  CsvSeries csv_;
};

}  // namespace dem
