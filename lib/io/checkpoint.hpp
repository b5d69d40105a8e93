#pragma once
// The HDF5 checkpoint (DESIGN.md "The checkpoint"; schema in docs/checkpoint.md): everything needed
// to continue a run bit-exactly. Written atomically (temporary name, fsync, rename); every dataset
// carries a Fletcher32 checksum so damage is detected instead of read as wrong numbers.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace dem {

// 2: wall motions compose translation, time table, vibration, rotation; 3: [[pair]] overrides
// (/pairs), contact properties named by their models' keys.
inline constexpr int kCheckpointSchema = 4;
inline constexpr int kOldestReadableSchema = 2;
inline constexpr const char* kCheckpointFormat = "dem-checkpoint";

// Where a run-stage run stands, so that --restart continues exactly.
struct RunInfo {
  std::string stage;                 // stage name, or the tool name outside run-stage ("gen-primary", ...)
  std::int64_t stage_start_step = 0; // step count when the stage began
  std::int64_t stage_steps = 0;      // steps the stage takes in all
  double stage_start_time = 0;       // [s]
  std::vector<double> frame_times;   // times of the VTK frames written so far in this stage [s]
  std::vector<double> servo_integral;  // per [[stage.servo]]: its integral action [m/s] (ServoGroup)
  std::string input_path;  // the --in this run started from ("" for gen-primary)
  std::string input_seal;  // its seal_fingerprint (io/file_seal.hpp), "" for gen-primary
  std::vector<std::int64_t> insert_count;     // per [[stage.insert]]: particles inserted so far
  std::vector<std::int64_t> insert_deferred;  // per [[stage.insert]]: particle-events that found no room
  std::int64_t stage_start_bonds = -1;        // intact bonds when the stage began (health log); -1 = unknown
  std::vector<double> energy;  // the energy log's ledger (EnergyLedger::values) [J]; empty: no energy log
  std::int64_t sink_count = 0;  // [stage.sink]: particles removed so far in this stage
  double sink_mass = 0;         // [stage.sink]: their mass [kg] (generation/sink.hpp)
};

struct CheckpointMeta {
  std::string writer;          // tool that wrote the file
  std::string writer_version;  // filled on read; kVersion on write
  std::string scene_path, scene_text;
  std::string scene_walls;  // Scene::walls_fingerprint(); empty when read from a file written before it existed
  std::vector<std::string> scene_files;  // Scene::files
  // On read: the file holds /run/input_seal and /scene/files (files written before them do not:
  // their input is unknown).
  bool inputs_recorded = false;
  RunInfo run;
};

void write_checkpoint(const std::string& path, const Simulation& sim, const CheckpointMeta& meta);
// Throws IoError for a missing, truncated, damaged or foreign file, with the reason.
void read_checkpoint(const std::string& path, Simulation& sim, CheckpointMeta& meta);

}  // namespace dem
