#pragma once
// Per-wall force and torque time series (SPEC §3), written as CSV while a stage runs. A mesh wall
// is the sum over its elements (`drum.0`, `drum.1`, ... give one row `drum`); box faces
// (`box.zmax`) and polygons are walls of their own. Partial file and restart: io/csv_series.hpp.
#include <cstdint>
#include <string>
#include <vector>

#include "io/csv_series.hpp"
#include "sim/simulation.hpp"

namespace dem {

// The walls as the logs name them: mesh elements NAME.0, NAME.1, ... make one wall NAME; box faces
// (box.zmax) and polygons are walls of their own. `group_of[e]` is element e's index into `names`.
struct WallGroups {
  std::vector<std::string> names;
  std::vector<int> group_of;
};
WallGroups wall_groups(const std::vector<Wall>& walls);

class WallLog {
 public:
  // `path` empty: no log. `resume_step` >= 0: continue the partial file of an interrupted run,
  // dropping its rows after that step.
  WallLog(const std::string& path, const std::vector<Wall>& walls, std::int64_t every, std::int64_t resume_step);

  // Appends one row per wall if `steps_done` is a multiple of `every` or `last`.
  void record(const Simulation& sim, std::int64_t steps_done, bool last);
  void finish() { csv_.finish(); }  // closes the file and renames it into place
  void discard() { csv_.discard(); }  // a failed run that no restart can continue

 private:
  CsvSeries csv_;
  std::int64_t every_ = 1;
  WallGroups groups_;
};

}  // namespace dem
