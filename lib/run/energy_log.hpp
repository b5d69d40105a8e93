#pragma once
// The energy log of run-stage (sim/energy_ledger.hpp, docs/physics.md eq. P29-P39): when a stage
// asks for it (energy_every, or run-stage --energy-every), one CSV row (OUT with .energy.csv) every
// `every` steps and at the last step of the stage: the energy held, dissipated, released and put
// in since the first step, and the balance error. Partial file and restart as the other series
// (io/csv_series.hpp); the ledger's sums travel in the periodic checkpoint, so a resumed run's file
// equals an uninterrupted run's.
#include <cstdint>
#include <string>

#include "core/interval.hpp"
#include "io/csv_series.hpp"
#include "sim/simulation.hpp"

namespace dem {

// The energy log that belongs to an output path: "x.h5" -> "x.energy.csv".
std::string energy_path(const std::string& out);

// Steps between energy rows: `cli` if given (run-stage --energy-every), else the stage's
// energy_every if given, else 0: no energy log.
std::int64_t energy_interval(const Interval& cli, const Interval& scene, double dt);

class EnergyLog {
 public:
  // `every` 0: no log (every call does nothing).
  EnergyLog(const std::string& path, std::int64_t every, std::int64_t resume_step);

  bool active() const { return csv_.active(); }
  // Whether the step that ends with `steps_done` steps of the stage done writes a row.
  bool due(std::int64_t steps_done, bool last) const { return csv_.active() && (steps_done % every_ == 0 || last); }
  void record(const Simulation& sim, std::int64_t steps_done, bool last) {
    if (due(steps_done, last)) write(sim);
  }
  void finish() { csv_.finish(); }
  void discard() { csv_.discard(); }

 private:
  void write(const Simulation& sim);
  CsvSeries csv_;
  std::int64_t every_;
};

}  // namespace dem
