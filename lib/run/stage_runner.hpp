#pragma once
// run-stage: one stage of a scene from a checkpoint to a checkpoint, with periodic checkpoints,
// exact resumption (--restart), VTK frames, and a clean stop on Ctrl-C or SIGTERM (run/interrupt.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "core/interval.hpp"

namespace dem {

struct StageOptions {
  std::string scene;  // scene file
  std::string stage;  // stage name in the scene
  std::string in;     // input checkpoint
  std::string out;    // output checkpoint, written when the stage completes
  std::string vtk_dir;               // VTK frames and .pvd series; empty = none
  Interval checkpoint_every;          // between periodic checkpoints; not given = none
  double checkpoint_minutes = 30;    // wall-clock minutes between periodic checkpoints; 0 = none
  bool restart = false;              // resume from the periodic checkpoint if there is one
  std::string wall_forces;           // per-wall force and torque CSV; empty = none
  Interval wall_forces_every = steps(100);  // between its rows
  std::string track;                 // tracked particles CSV; empty = none
  std::vector<std::int64_t> track_ids;   // their ids
  Interval track_every = steps(100);        // between its rows
  Interval health_every;  // between health rows (OUT with .health.csv); not given = the scene's
  Interval energy_every;  // between energy rows (OUT with .energy.csv); not given = the scene's (none without)
  bool quiet = false;
  std::string command;  // the command line as given, for the resume command printed on Ctrl-C
};

// The periodic checkpoint that belongs to an output path: "x.h5" -> "x.restart.h5".
std::string restart_path(const std::string& out);

void run_stage(const StageOptions& options);

}  // namespace dem
