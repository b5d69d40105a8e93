// run-stage: run one stage of a scene from a checkpoint to a checkpoint.
#include "run/stage_runner.hpp"
#include "tool_main.hpp"

int main(int argc, char** argv) {
  CLI::App app("Run one [[stage]] of a scene from a checkpoint to a checkpoint, with periodic checkpoints, exact restart and VTK frames.",
               "run-stage");
  dem::StageOptions o;
  int threads = 0;
  app.add_option("--scene", o.scene, "scene file (TOML)")->required()->check(CLI::ExistingFile);
  app.add_option("--stage", o.stage, "name of the [[stage]] to run")->required();
  app.add_option("--in", o.in, "input checkpoint (HDF5)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", o.out, "output checkpoint (HDF5), written atomically when the stage completes")->required();
  app.add_option("--vtk", o.vtk_dir, "directory for VTK frames and .pvd series");
  dem::add_interval_option(app, "--checkpoint-every", o.checkpoint_every, "between periodic checkpoints (OUT with .restart.h5)", true);
  app.add_option("--checkpoint-minutes", o.checkpoint_minutes,
                 "wall-clock minutes between periodic checkpoints (default 30; 0 = none); Ctrl-C writes one too unless both are off")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--restart", o.restart, "resume from the periodic checkpoint if one exists");
  app.add_option("--wall-forces", o.wall_forces, "per-wall force and torque time series (CSV)");
  dem::add_interval_option(app, "--wall-forces-every", o.wall_forces_every, "between rows of --wall-forces (default 100 steps)");
  auto* track = app.add_option("--track", o.track, "time series of chosen particles (CSV): position, velocity, spin");
  auto* track_ids = app.add_option("--track-ids", o.track_ids, "ids of the particles for --track, e.g. 0,17")
                        ->delimiter(',')
                        ->check(CLI::NonNegativeNumber);
  track->needs(track_ids);
  track_ids->needs(track);
  dem::add_interval_option(app, "--track-every", o.track_every, "between rows of --track (default 100 steps)")->needs(track);
  dem::add_interval_option(app, "--health-every", o.health_every,
                           "between rows of the health log OUT with .health.csv (default: the stage's health_every, else a hundredth of "
                           "the stage, at least 500 steps)");
  dem::add_interval_option(app, "--energy-every", o.energy_every,
                           "between rows of the energy log OUT with .energy.csv (default: the stage's energy_every; without either, no "
                           "energy log)");
  app.add_flag("--quiet", o.quiet, "no progress output");
  dem::add_common_options(app, threads);
  o.command = dem::shell_command(argc, argv);
  return dem::run_tool(app, argc, argv, threads, [&] { dem::run_stage(o); });
}
