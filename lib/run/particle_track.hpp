#pragma once
// Time series of chosen particles (by id) written as CSV while a stage runs: position, velocity
// and angular velocity, e.g. the large sphere of the segregation case or the bouncing sphere of
// the damping check. Partial file and restart: io/csv_series.hpp.
#include <cstdint>
#include <string>
#include <vector>

#include "io/csv_series.hpp"
#include "sim/simulation.hpp"

namespace dem {

class ParticleTrack {
 public:
  // `path` empty: no output. Every id must exist in `sim` (InputError naming the missing one).
  ParticleTrack(const std::string& path, const std::vector<Index>& ids, const Simulation& sim, std::int64_t every,
                std::int64_t resume_step);

  // Appends one row per tracked particle if `steps_done` is a multiple of `every`, or `first`/`last`.
  void record(const Simulation& sim, std::int64_t steps_done, bool first_or_last);
  void finish() { csv_.finish(); }
  void discard() { csv_.discard(); }  // a failed run that no restart can continue

 private:
  std::size_t index_of(const Particles& p, std::size_t k);  // current storage index of ids_[k]
  std::vector<Index> ids_;
  std::vector<std::size_t> index_;  // last known storage index of each id (checked before the file opens)
  std::int64_t every_ = 1;
  CsvSeries csv_;
};

}  // namespace dem
