#include "run/stage_runner.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "control/servo.hpp"
#include "core/error.hpp"
#include "core/version.hpp"
#include "generation/fibre_placement.hpp"
#include "generation/fill.hpp"
#include "generation/insertion.hpp"
#include "generation/sink.hpp"
#include "io/checkpoint.hpp"
#include "io/file_seal.hpp"
#include "io/output_paths.hpp"
#include "io/scene_parser.hpp"
#include "io/vtk_output.hpp"
#include "run/energy_log.hpp"
#include "run/frames.hpp"
#include "run/health_log.hpp"
#include "run/interrupt.hpp"
#include "run/particle_groups.hpp"
#include "run/particle_track.hpp"
#include "run/progress.hpp"
#include "run/setup.hpp"
#include "run/sink_log.hpp"
#include "run/start_checks.hpp"
#include "run/wall_log.hpp"

namespace dem {

std::string restart_path(const std::string& out) { return beside_output(out, ".restart.h5"); }

namespace {

void apply_actions(Simulation& sim, const StageSpec& stage) {
  Particles& p = sim.particles;
  for (const ActionSpec& a : stage.actions) {
    if (a.kind == ActionSpec::Kind::ResetReference) {
      for (std::size_t k = 0; k < p.size(); ++k) p.x_ref[k] = sim.unwrapped_position(k);
    } else if (a.kind == ActionSpec::Kind::Bond) {
      const std::size_t n = sim.bond_present_contacts(a.walls, a.gap);
      std::cerr << "stage " << stage.name << ": bonded " << n << " contacts\n";
    } else if (a.kind == ActionSpec::Kind::Fix || a.kind == ActionSpec::Kind::Release) {
      const bool fix = a.kind == ActionSpec::Kind::Fix;
      const std::size_t n = set_fixed(sim, a.region ? &*a.region : nullptr, a.inside, fix);
      std::cerr << "stage " << stage.name << ": " << (fix ? "fixed " : "released ") << n << " particles\n";
    } else {
      const std::size_t removed = remove_particles(sim, *a.region, a.inside);
      std::cerr << "stage " << stage.name << ": removed " << removed << " particles, " << p.size() << " remain\n";
    }
  }
}

// [[stage.set_velocity]] then [[stage.prescribe]], in file order, once at the stage start (a
// resumed run finds their effect in the periodic checkpoint: velocities and the prescribed flags).
void start_velocities(Simulation& sim, const Scene& scene, const StageSpec& stage) {
  for (const char* key : {"set_velocity", "prescribe"}) {
    const bool prescribe = std::string(key) == "prescribe";
    const std::vector<VelocitySpec>& list = prescribe ? stage.prescribes : stage.set_velocities;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::size_t n = prescribe ? start_prescribed(sim, list[k]) : set_group_velocity(sim, list[k]);
      if (n == 0)
        throw InputError(scene.path + ": stage." + key + "[" + std::to_string(k) + "] of stage \"" + stage.name + "\" selects no particle (" +
                         describe_group(sim, list[k].group) + "); check the material, ids or region against the particles of --in");
      std::cerr << "stage " << stage.name << ": " << (prescribe ? "prescribed the velocity of " : "set the velocity of ") << n
                << " particles (" << describe_group(sim, list[k].group) << ")\n";
    }
  }
}

// [stage.fibres]: placed once, at the stage start (a resumed run finds them in its checkpoint).
void start_fibres(Simulation& sim, const Scene& scene, const StageSpec& stage) {
  if (sim.periodic.any())
    throw InputError(scene.path + ": stage \"" + stage.name + "\": [stage.fibres] with periodic boundaries ([simulation.periodic]) is not supported");
  FibrePlacement placed;
  try {
    placed = place_fibres(sim.particles, *stage.fibres, sim.fibres);
  } catch (const std::runtime_error& e) {
    throw InputError(scene.path + ": stage \"" + stage.name + "\": [stage.fibres]: " + e.what());
  }
  std::cerr << "stage " << stage.name << ": placed " << placed.placed << " fibres with " << placed.ties << " ties (volume fraction "
            << placed.volume / placed.box_volume << " of the particles' bounding box; " << placed.redrawn << " drawn again)\n";
}

void start_motions(Simulation& sim, const StageSpec& stage) {
  for (Wall& w : sim.walls) {
    WallMotion m;  // fixed unless the stage says otherwise; matching entries compose in file order
    for (const MotionSpec& ms : stage.motions)
      if (wall_matches(w.name, ms.wall)) ms.apply_to(m);
    w.start_motion(m, sim.time);
  }
}

// The stage's servo groups, from the scene's walls as given (not their current positions), so that
// a resumed run computes the same directions to the bit; servo walls only translate, which does
// not change them. Their areas are taken each step from the walls and particles now
// (update_areas), which a periodic checkpoint holds exactly.
std::vector<ServoGroup> stage_servos(const Simulation& sim, const Scene& scene, const StageSpec& stage) {
  std::vector<Wall> as_given;
  for (const WallSpec& w : scene.walls) as_given.push_back(Wall{w.name, w.material, w.vertices, {}});
  std::vector<ServoGroup> groups;
  for (const ServoSpec& s : stage.servos) {
    ServoGroup g = servo_group(as_given, 0, s.wall, particle_centroid(sim), s.direction ? &*s.direction : nullptr);
    g.target = s.target_stress;
    g.max_speed = s.max_speed;
    g.gain = s.gain;
    g.integral_time = s.integral_time;
    groups.push_back(g);
  }
  return groups;
}

// A periodic checkpoint continues exactly the run that wrote it: the same toolkit version, --in,
// scene values (its text, or one that differs only in comments and layout), walls, files the
// scene reads and stage. Anything else would give another run's result
// under this run's name, so it is refused (InputError) with what differs and how to start over.
void check_resumable(const StageOptions& o, const Scene& scene, const StageSpec& stage, const std::string& restart_file,
                     const CheckpointMeta& meta) {
  const std::string start_over = " (to start the stage over from --in, delete " + restart_file + " or run without --restart)";
  auto refuse = [&](const std::string& what) { throw InputError("--restart: the periodic checkpoint " + restart_file + " " + what + start_over); };
  if (meta.writer_version != kVersion)
    refuse("was written by run-stage " + (meta.writer_version.empty() ? std::string("of unknown version") : meta.writer_version) +
           ", this is " + kVersion + "; an exact restart needs the same version");
  if (!meta.inputs_recorded)
    refuse("does not record the --in checkpoint and the files it was started from (written before run-stage recorded them), so it "
           "cannot be checked against this run");
  if (meta.run.stage != stage.name) refuse("belongs to stage \"" + meta.run.stage + "\", not \"" + stage.name + "\"");
  std::string in_seal;
  try {
    in_seal = seal_fingerprint(o.in);
  } catch (const IoError& e) {
    refuse("was started from --in " + meta.run.input_path + " (" + meta.run.input_seal + "), and --in " + o.in +
           " cannot be read to compare: " + e.what());
  }
  if (in_seal != meta.run.input_seal)
    refuse("was started from a different input: --in " + meta.run.input_path + " (" + meta.run.input_seal + ") then, --in " + o.in + " (" +
           in_seal + ") now");
  if (meta.scene_text != scene.text) {
    if (!same_scene_values(meta.scene_text, scene.text))
      refuse("was written with another scene: the scene file " + o.scene + " holds other values than the one the periodic checkpoint holds");
    // An edited comment or layout changes no value: the run is the same one.
    std::cerr << "run-stage: --restart: the scene file " << o.scene
              << " differs from the one the periodic checkpoint holds only in comments and layout (the same values): resuming\n";
  }
  if (!meta.scene_walls.empty() && meta.scene_walls != scene.walls_fingerprint())
    refuse("was written with other walls: the walls " + o.scene + " builds differ (was a wall's STL file edited?)");
  // Entries are "fnv1a64=<hex> size=N PATH": compare the contents, not the path (the same file may be reached by another path).
  auto contents = [](const std::string& entry) { return entry.substr(0, entry.find(' ', entry.find(' ') + 1)); };
  auto path_of = [](const std::string& entry) { return entry.substr(entry.find(' ', entry.find(' ') + 1) + 1); };
  const std::vector<std::string>& then = meta.scene_files;
  const std::vector<std::string>& now = scene.files;
  for (std::size_t k = 0; k < std::max(then.size(), now.size()); ++k) {
    if (k >= then.size()) refuse("was written when the scene read no file " + path_of(now[k]) + " (" + contents(now[k]) + ")");
    if (k >= now.size()) refuse("was written when the scene also read " + path_of(then[k]) + " (" + contents(then[k]) + "), which it no longer reads");
    if (contents(then[k]) != contents(now[k]))
      refuse("was written when the file " + path_of(then[k]) + " the scene reads held other bytes (" + contents(then[k]) + " then, " +
             path_of(now[k]) + ": " + contents(now[k]) + " now)");
  }
}

// The time step must hold for the particles a stage will insert too: the particles now and, per
// [[stage.insert]] material, one of its smallest and one of its largest radius (eq. 2.48 takes
// the least mass and the largest stiffness).
Simulation with_inserted_sizes(const Simulation& sim, const StageSpec& stage) {
  if (stage.inserts.empty()) return sim;
  Simulation probe;
  probe.materials = sim.materials;
  probe.params = sim.params;
  probe.particles = sim.particles;
  for (const InsertSpec& s : stage.inserts)
    for (const auto& [m, f] : s.material_fractions)
      for (double a : {s.radius_min, s.radius_max}) probe.particles.add(-1, Vec3::Zero(), a, sim.materials.materials()[m].density, m);
  return probe;
}

}  // namespace

void run_stage(const StageOptions& o) {
  const Scene scene = read_scene_file(o.scene);
  const StageSpec* stage = scene.stage(o.stage);
  if (!stage) {
    std::string list;
    for (const StageSpec& s : scene.stages) list += (list.empty() ? "" : ", ") + s.name;
    throw InputError(o.scene + ": no [[stage]] named \"" + o.stage + "\" (defined: " + (list.empty() ? "none" : list) + ")");
  }
  print_scene_warnings(scene, "run-stage");
  const std::string restart_file = restart_path(o.out);
  // Every output is checked before anything runs: an unwritable one fails now, not after the run.
  check_output_file(o.out, "--out");
  if (o.checkpoint_every.given() || o.checkpoint_minutes > 0) check_output_file(restart_file, "--out (its periodic checkpoint)");
  check_output_dir(o.vtk_dir, "--vtk");
  check_output_file(o.wall_forces, "--wall-forces");
  check_output_file(o.track, "--track");
  const std::string health_file = health_path(o.out);
  check_output_file(health_file, "--out (its health log)");
  const std::string energy_file = energy_path(o.out);
  if (o.energy_every.given() || stage->energy_every.given()) check_output_file(energy_file, "--out (its energy log)");
  const std::string sink_file = stage->sink ? sink_path(o.out) : std::string();
  check_output_file(sink_file, "--out (its sink log)");
  const std::string walls_fingerprint = scene.walls_fingerprint();
  Simulation sim;
  CheckpointMeta meta;
  if (o.restart && std::filesystem::exists(restart_file)) {
    read_checkpoint(restart_file, sim, meta);
    check_resumable(o, scene, *stage, restart_file, meta);
    // The same scene text gives the same contact constants, [[pair]] entries included.
    sim.materials = MaterialTable(scene.materials, scene.mixing, scene.pairs);
    if (!o.quiet) std::cerr << "run-stage: resuming stage " << stage->name << " at step " << sim.step << " from " << restart_file << "\n";
  } else {
    if (o.restart && !o.quiet) std::cerr << "run-stage: no periodic checkpoint " << restart_file << ", starting from " << o.in << "\n";
    read_checkpoint(o.in, sim, meta);
    sim.particles.void_fraction.clear();  // an earlier stage's: this one computes its own at its first step
    adopt_scene(sim, scene);
    apply_actions(sim, *stage);
    if (stage->fibres) start_fibres(sim, scene, *stage);
    start_velocities(sim, scene, *stage);
    check_inside_walls(sim, scene, o.in);
    sim.dt = choose_time_step(with_inserted_sizes(sim, *stage), scene.simulation);
    start_motions(sim, *stage);
    meta.run = RunInfo{stage->name, sim.step, static_cast<std::int64_t>(std::ceil(stage->duration / sim.dt - 1e-9)), sim.time, {}, {},
                       o.in, seal_fingerprint(o.in), {}, {}, -1, {}};
    meta.run.stage_start_bonds = static_cast<std::int64_t>(intact_bonds(sim));
  }
  // A stage's own gravity (a resumed run's checkpoint holds it already; set again all the same).
  if (stage->gravity) sim.params.gravity = *stage->gravity;
  // The stage's fluid, or none; its void fractions are the checkpoint's when resumed, computed
  // afresh at a stage start.
  sim.params.fluid = stage->fluid ? *stage->fluid : FluidParams{};
  if (!sim.params.fluid.on()) sim.particles.void_fraction.clear();
  // A fresh start only: a resumed run goes on with the step its start accepted (restart = uninterrupted run).
  if (sim.step == meta.run.stage_start_step) check_drag_step(sim, scene.simulation.force_time_step, stage->name);
  const StartChecks checks(sim);
  checks.print("run-stage");
  meta.writer = "run-stage";
  meta.scene_path = scene.path;
  meta.scene_text = scene.text;
  meta.scene_walls = walls_fingerprint;
  meta.scene_files = scene.files;
  RunInfo& run = meta.run;

  std::vector<ServoGroup> servos = stage_servos(sim, scene, *stage);
  if (!run.servo_integral.empty()) {  // resumed: the integral actions where the checkpoint left them
    if (run.servo_integral.size() != servos.size())
      throw IoError(restart_file + ": /run/servo_integral holds " + std::to_string(run.servo_integral.size()) +
                    " values, the stage has " + std::to_string(servos.size()) + " servos");
    for (std::size_t k = 0; k < servos.size(); ++k) servos[k].integral = run.servo_integral[k];
  }
  auto keep_integrals = [&]() {
    run.servo_integral.resize(servos.size());
    for (std::size_t k = 0; k < servos.size(); ++k) run.servo_integral[k] = servos[k].integral;
  };
  // Insertion: the counts inserted so far come from the periodic checkpoint when resumed.
  if (run.insert_count.empty()) run.insert_count.assign(stage->inserts.size(), 0), run.insert_deferred.assign(stage->inserts.size(), 0);
  if (run.insert_count.size() != stage->inserts.size() || run.insert_deferred.size() != stage->inserts.size())
    throw IoError(restart_file + ": /run/insert_count holds " + std::to_string(run.insert_count.size()) + " values, the stage has " +
                  std::to_string(stage->inserts.size()) + " [[stage.insert]] groups");
  std::vector<InsertGroup> inserts;
  for (std::size_t k = 0; k < stage->inserts.size(); ++k)
    inserts.emplace_back(stage->inserts[k], sim.materials, run.insert_count[k], run.insert_deferred[k]);
  auto keep_insert_counts = [&]() {
    for (std::size_t k = 0; k < inserts.size(); ++k) run.insert_count[k] = inserts[k].count(), run.insert_deferred[k] = inserts[k].deferred();
  };
  // The sink's totals so far: from the periodic checkpoint when resumed.
  SinkTotals sunk{run.sink_count, run.sink_mass};
  auto keep_sink = [&]() { run.sink_count = sunk.count, run.sink_mass = sunk.mass; };
  double k_max = 0, c_max = 0;
  servo_constants(sim, k_max, c_max);
  const std::int64_t resume_step = sim.step > run.stage_start_step ? sim.step : -1;
  // The track first: a missing id is an error before any file is opened.
  ParticleTrack track(o.track, o.track_ids, sim, o.track_every.steps(sim.dt), resume_step);
  WallLog wall_log(o.wall_forces, sim.walls, o.wall_forces_every.steps(sim.dt), resume_step);
  const std::int64_t health_every = health_interval(o.health_every, stage->health_every, stage->duration, sim.dt);
  HealthLog health(health_file, sim.walls, health_every, run.stage_steps, resume_step, run.stage_start_bonds, o.quiet);
  const std::int64_t energy_every = energy_interval(o.energy_every, stage->energy_every, sim.dt);
  EnergyLog energy(energy_file, energy_every, resume_step);
  SinkLog sink_log(sink_file, resume_step);
  sim.ledger = EnergyLedger{};
  sim.ledger.on = energy.active();
  if (sim.ledger.on && !run.energy.empty()) {  // resumed: the sums where the periodic checkpoint left them
    try {
      sim.ledger.from_values(run.energy);
    } catch (const std::invalid_argument& e) {
      throw IoError(restart_file + ": /run/energy " + e.what());
    }
    sim.ledger.on = true;
  }
  auto keep_energy = [&]() { run.energy = sim.ledger.on ? sim.ledger.values() : std::vector<double>{}; };
  if (!o.quiet)
    std::cerr << "run-stage: stage " << stage->name << ": time step " << sim.dt << " s (" << sim.dt / sim.critical_time_step()
              << " of the critical " << sim.critical_time_step() << " s of docs/physics.md eq. P5), " << run.stage_steps << " steps to t = "
              << run.stage_start_time + stage->duration << " s; health every " << health_every << " steps (" << health_every * sim.dt
              << " s) in " << health_file << (energy.active() ? "; energy every " + std::to_string(energy_every) + " steps in " + energy_file : "")
              << "\n";
  FrameWriter frames(o.vtk_dir, stage->name);
  if (resume_step < 0) frames.discard();  // a fresh start: staged frames of an earlier run are stale
  // Partial outputs (staged frames, .partial CSV files) are kept for a restart while a periodic
  // checkpoint of this run exists, and removed when a run that none can continue fails.
  bool have_checkpoint = resume_step >= 0;
  const StopOnSignal stop;
  try {
    if (resume_step < 0) track.record(sim, 0, true);  // the state at the stage start
    if (resume_step < 0) sink_log.record(sim, sunk, 0, true);
    const std::int64_t interval = stage->output_every.given() ? stage->output_every.steps(sim.dt) : run.stage_steps;
    auto maybe_frame = [&]() {
      const std::int64_t s = sim.step - run.stage_start_step;
      if (s % interval == 0 || s == run.stage_steps) {
        // A frame index is known from the step, so a resumed run rewrites exactly the same files.
        const std::size_t index = static_cast<std::size_t>(s / interval) + (s % interval != 0);
        run.frame_times.resize(index);
        run.frame_times.push_back(sim.time);
        frames.write(sim, run.frame_times);
      }
    };
    if (sim.step == run.stage_start_step) maybe_frame();

    Progress progress("run-stage " + stage->name, run.stage_steps, o.quiet);
    // Nothing in a stage reads the pair contacts' forces: post-processing computes them on a copy
    // (contact_forces_at_state), checkpoints keep keys, springs and bonds.
    sim.params.keep_pair_results = false;
    const std::int64_t end = run.stage_start_step + run.stage_steps;
    const bool periodic = o.checkpoint_every.given() || o.checkpoint_minutes > 0;
    const std::int64_t checkpoint_every = o.checkpoint_every.steps(sim.dt);
    auto last_checkpoint = std::chrono::steady_clock::now();
    std::int64_t checkpoint_step = have_checkpoint ? sim.step : -1;
    // For the summary: the particle-steps and wall time of this process's part of the stage.
    const auto loop_start = std::chrono::steady_clock::now();
    const std::int64_t loop_first_step = sim.step;
    double particle_steps = 0;
    auto write_periodic = [&]() {
      keep_integrals();
      keep_insert_counts();
      keep_energy();
      keep_sink();
      write_checkpoint(restart_file, sim, meta);
      have_checkpoint = true;
      checkpoint_step = sim.step;
      last_checkpoint = std::chrono::steady_clock::now();
    };
    while (sim.step < end) {
      // Particles due by now, before the step (a periodic checkpoint is written after a step, so a
      // resumed run makes this event first, as the uninterrupted one does).
      if (!inserts.empty()) {
        const std::size_t before = sim.particles.size();
        if (insert_due(sim, inserts, sim.step - run.stage_start_step, sim.time - run.stage_start_time)) sim.account_inserted(before);
      }
      particle_steps += static_cast<double>(sim.particles.size());
      sim.ledger.measure_now = energy.due(sim.step + 1 - run.stage_start_step, sim.step + 1 == end);
      checks.guard([&] { sim.advance(); });
      // Servo speeds for the next step from this step's forces: the periodic checkpoint holds them as
      // the walls' motion, so a resumed run continues exactly.
      if (!servos.empty()) drive_servos(sim, servos, k_max, c_max);
      const std::int64_t done = sim.step - run.stage_start_step;
      // The sink after the step, so that a periodic checkpoint (written after it) holds its event.
      if (stage->sink) sink_log.record(sim, sunk, sink_due(sim, *stage->sink, done, sunk), sim.step == end);
      maybe_frame();
      wall_log.record(sim, done, sim.step == end);
      track.record(sim, done, sim.step == end);
      health.record(sim, done, sim.step == end);
      energy.record(sim, done, sim.step == end);
      progress.update(done, sim.time);
      if (sim.step == end) break;
      const bool by_steps = checkpoint_every > 0 && done % checkpoint_every == 0;
      // The clock is read every 64 steps only (as Progress does).
      const bool by_time = o.checkpoint_minutes > 0 && (done & 63) == 0 &&
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >= 60 * o.checkpoint_minutes;
      if (by_steps || by_time) write_periodic();
      if (const int signal = StopOnSignal::received()) {
        if (periodic && checkpoint_step != sim.step) write_periodic();
        std::ostringstream m;
        m << "interrupted by " << StopOnSignal::name(signal) << " after step " << sim.step << " (" << done << " of " << run.stage_steps
          << " steps of stage " << stage->name << ", t = " << sim.time << " s); ";
        if (have_checkpoint) {
          const bool has_flag = (" " + o.command + " ").find(" --restart ") != std::string::npos;
          m << "the periodic checkpoint " << restart_file << " holds step " << checkpoint_step << ". To resume, run:\n  " << o.command
            << (has_flag ? "" : " --restart");
        } else {
          m << "no periodic checkpoint (--checkpoint-minutes 0 and no --checkpoint-every), nothing written. To run the stage again, run:\n  "
            << o.command;
        }
        throw Interrupted(m.str());
      }
    }
    progress.finish(sim.step - run.stage_start_step, sim.time);
    if (!servos.empty()) {
      // The servo walls stop where they are; report what they hold.
      update_areas(sim, servos);
      const std::vector<WallLoad> f = sim.wall_loads();
      for (std::size_t k = 0; k < servos.size(); ++k) {
        for (std::size_t e : servos[k].elements) sim.walls[e].start_motion(WallMotion{}, sim.time);
        if (!o.quiet)
          std::cerr << "run-stage: servo " << stage->servos[k].wall << " holds " << servos[k].stress(f) << " Pa (target "
                    << servos[k].target << " Pa)\n";
      }
    }
    if (!stage->prescribes.empty()) {
      // What the rest exerted on the prescribed particles at the last step; then they are free.
      const Vec3 f = force_on_prescribed(sim);
      const std::size_t n = end_prescribed(sim);
      if (!o.quiet)
        std::cerr << "run-stage: force on the " << n << " prescribed particles at the end (contacts and walls): [" << f.x() << ", " << f.y()
                  << ", " << f.z() << "] N; they move on freely\n";
    }
    // Before the checkpoint: a finished checkpoint means finished outputs (make).
    wall_log.finish();
    track.finish();
    health.finish();
    energy.finish();
    sink_log.finish();
    frames.commit(run.frame_times.size());
    if (!inserts.empty() && !o.quiet) std::cerr << "run-stage: " << insert_report(inserts, sim.time - run.stage_start_time) << "\n";
    if (stage->sink && !o.quiet)
      std::cerr << "run-stage: sink: removed " << sunk.count << " particles, " << sunk.mass << " kg (" << sink_file << ")\n";
    keep_integrals();
    keep_insert_counts();
    keep_energy();
    keep_sink();
    write_checkpoint(o.out, sim, meta);
    if (!o.quiet) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
      std::ostringstream m;
      m.precision(3);
      m << "run-stage: stage " << stage->name << " done: " << sim.step - loop_first_step << " steps";
      if (loop_first_step != run.stage_start_step) m << " (resumed at step " << loop_first_step - run.stage_start_step << ")";
      m << " in " << wall << " s wall time, " << (wall > 0 ? particle_steps / wall : 0.0) << " particle-steps/s";
      m << " on " << sim.step_threads() << (sim.step_threads() == 1 ? " thread" : " threads");  // the last step's
      if (!health.last_line().empty()) m << "; at the end " << health.last_line();
      m << "\n";
      std::cerr << m.str();
    }
  } catch (...) {
    if (!have_checkpoint) {
      frames.discard();
      wall_log.discard();
      track.discard();
      health.discard();
      energy.discard();
      sink_log.discard();
    }
    throw;
  }
  std::remove(restart_file.c_str());
}

}  // namespace dem
