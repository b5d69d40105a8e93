#include "run/generate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <numbers>
#include <random>
#include <sstream>

#include "control/servo.hpp"
#include "core/error.hpp"
#include "generation/fill.hpp"
#include "generation/size_distribution.hpp"
#include "io/atomic_write.hpp"
#include "io/checkpoint.hpp"
#include "io/file_seal.hpp"
#include "io/output_paths.hpp"
#include "io/scene_parser.hpp"
#include "run/progress.hpp"
#include "run/settle.hpp"
#include "run/setup.hpp"
#include "run/start_checks.hpp"
#include "walls/container.hpp"

namespace dem {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Bulk porosity of the bed: 1 - solid volume / container volume, the container being the convex
// region bounded by the walls' planes, cut at the top of the highest sphere against gravity (an
// open or half-empty box would otherwise count its empty headspace as pores); walls/container.hpp.
double porosity(const Simulation& sim) {
  if (sim.walls.empty() || sim.particles.size() == 0) return 0;
  const double volume = Container(sim.walls, sim.time, sim.particles, sim.params.gravity).volume();
  double solid = 0;
  for (double a : sim.particles.radius) solid += sphere_volume(a);
  return volume > 0 ? 1 - solid / volume : 0;
}

void report(const char* tool, const Simulation& sim, const SettleResult& s, double wall_seconds) {
  std::printf("%s: %zu particles, %lld steps of dt = %.4g s (t = %.4g s), settled: %s (KE ratio %.3g), porosity %.4f, "
              "coordination %.3f, %.2f s wall\n",
              tool, sim.particles.size(), static_cast<long long>(s.steps), sim.dt, sim.time, s.skipped ? "skipped (max_time = 0)" : s.converged ? "yes" : "no (time cap)",
              s.ke_ratio, porosity(sim), coordination_number(sim), wall_seconds);
}

CheckpointMeta meta_for(const char* tool, const Scene& scene, const std::string& in) {
  CheckpointMeta m;
  m.writer = tool;
  m.scene_path = scene.path;
  m.scene_text = scene.text;
  m.scene_walls = scene.walls_fingerprint();
  m.scene_files = scene.files;
  m.run.stage = tool;
  if (!in.empty()) m.run.input_path = in, m.run.input_seal = seal_fingerprint(in);
  return m;
}

Simulation load_under_scene(const std::string& path, const Scene& scene, WallPositions walls) {
  Simulation sim;
  CheckpointMeta meta;
  read_checkpoint(path, sim, meta);
  adopt_scene(sim, scene, walls);
  return sim;
}

// [[generation.cut]]: each region in turn removes the particles inside (or outside) it.
void apply_cuts(const char* tool, Simulation& sim, const std::vector<CutSpec>& cuts, const Scene& scene) {
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    const std::size_t removed = remove_particles(sim, cuts[k].region, cuts[k].inside);
    std::printf("%s: generation.cut[%zu] removed %zu particles, %zu remain\n", tool, k, removed, sim.particles.size());
    if (sim.particles.size() == 0)
      throw InputError(scene.path + ": generation.cut[" + std::to_string(k) + "] removed every particle");
  }
}

// The size distribution asked against the radii of the random spheres drawn (the last `count`
// particles), before settling and cuts: what the generator controls. Printed; returned for --sizes.
std::vector<SizeCheck> report_sizes(const char* tool, const Simulation& sim, const GenerationSpec& g, std::string& title) {
  const std::vector<double>& all = sim.particles.radius;
  const std::vector<double> radii(all.end() - g.count, all.end());
  const RadiusSampler sampler(g.size, g.radius_min, g.radius_max);
  title = std::string(tool) + ": size distribution " + size_kind_name(g.size.kind) + ", " + std::to_string(g.count) + " random spheres";
  std::printf("%s: asked, realised\n", title.c_str());
  std::vector<SizeCheck> rows = size_report(sampler, radii);
  for (const SizeCheck& c : rows) std::printf("%s:   %s: %.4g, %.4g\n", tool, c.what.c_str(), c.asked, c.realised);
  return rows;
}

// --sizes: the same lines as a table; diameter_m is empty for the moment rows.
void write_sizes_csv(const std::string& path, const std::string& title, const std::vector<SizeCheck>& rows) {
  write_text_atomically(path, [&](std::ostream& out) {
    out << "# " << title << " (docs/scene.md, [generation.size])\nquantity,diameter_m,asked,realised\n" << std::setprecision(10);
    for (const SizeCheck& c : rows) {
      out << c.what << ',';
      if (c.diameter > 0) out << c.diameter;
      out << ',' << c.asked << ',' << c.realised << '\n';
    }
  });
}

// The common end of gen-primary and copy-settle: time step, settle, cuts (gen-primary), checkpoint,
// report.
void settle_and_write(const char* tool, Simulation& sim, const SettleSpec& spec, const Scene& scene, const GenerateOptions& o,
                      Clock::time_point t0, const std::vector<CutSpec>& cuts = {}) {
  sim.dt = choose_time_step(sim, scene.simulation);
  const StartChecks checks(sim, std::string(tool) == "gen-primary" && scene.generation ? &*scene.generation : nullptr);
  checks.print(tool);
  const SettleResult s = checks.guard([&] { return settle(sim, spec, std::string(tool) + " settle", o.quiet); });
  apply_cuts(tool, sim, cuts, scene);
  write_checkpoint(o.out, sim, meta_for(tool, scene, o.in));
  report(tool, sim, s, seconds_since(t0));
}

// Each tool's start: the output path checked before the run (not after it), the scene read, its
// warnings printed, and the tool's own table required.
template <class Has>
Scene open_scene(const GenerateOptions& o, const char* tool, const char* table, Has has_table) {
  check_output_file(o.out, "--out");
  Scene scene = read_scene_file(o.scene);
  print_scene_warnings(scene, tool);
  if (!has_table(scene)) throw InputError(o.scene + ": " + tool + " needs a [" + table + "] table");
  return scene;
}

}  // namespace

void gen_primary(const GenerateOptions& o) {
  const auto t0 = Clock::now();
  const Scene scene = open_scene(o, "gen-primary", "generation", [](const Scene& sc) { return sc.generation.has_value(); });
  Simulation sim = simulation_from_scene(scene);
  std::mt19937_64 rng(scene.generation->seed);
  fill_random(sim, *scene.generation, rng);
  std::string title;
  const std::vector<SizeCheck> sizes = report_sizes("gen-primary", sim, *scene.generation, title);
  settle_and_write("gen-primary", sim, scene.generation->settle, scene, o, t0, scene.generation->cuts);
  if (!o.sizes.empty()) write_sizes_csv(o.sizes, title, sizes);
}

void copy_settle(const GenerateOptions& o) {
  const auto t0 = Clock::now();
  const Scene scene = open_scene(o, "copy-settle", "copy", [](const Scene& sc) { return sc.copy.has_value(); });
  Simulation sim = load_under_scene(o.in, scene, WallPositions::FromScene);  // the tiles need the scene's container
  const auto [lo, hi] = sphere_bounds(sim.particles);
  const Vec3 period = scene.copy->spacing.value_or(hi - lo);
  // Spheres may press into the container walls a little; copies then touch at the seams by at most
  // twice that. Allow 5 % of the smallest radius, reject anything more.
  double rmin = INFINITY;
  for (double a : sim.particles.radius) rmin = std::min(rmin, a);
  if (((hi - lo).array() > period.array() + 0.05 * rmin).any()) {
    std::ostringstream m;
    m << o.scene << ": copy.spacing = [" << period.transpose() << "] m is smaller than the input set's extent [" << (hi - lo).transpose()
      << "] m: the copies would overlap";
    throw InputError(m.str());
  }
  tile(sim, scene.copy->nx, scene.copy->ny, scene.copy->nz, period);
  sim.set_periodic(sim.periodic);  // copies past a periodic boundary re-enter at the other side
  settle_and_write("copy-settle", sim, scene.copy->settle, scene, o, t0);
}

void compact(const GenerateOptions& o) {
  const auto t0 = Clock::now();
  const Scene scene = open_scene(o, "compact", "compact", [](const Scene& sc) { return sc.compact.has_value(); });
  const CompactSpec& c = *scene.compact;
  Simulation sim = load_under_scene(o.in, scene, WallPositions::FromCheckpoint);
  sim.dt = choose_time_step(sim, scene.simulation);

  // Each named wall moves on its own along its normal towards the particles' centroid.
  std::vector<ServoGroup> servos;
  const Vec3 centroid = particle_centroid(sim);
  for (std::size_t k = 0; k < sim.walls.size(); ++k) {
    bool match = false;
    for (const std::string& name : c.walls) match = match || wall_matches(sim.walls[k].name, name);
    if (!match) continue;
    // The wall alone, not the group its name starts.
    ServoGroup g = servo_group({sim.walls[k]}, sim.time, sim.walls[k].name, centroid);
    g.elements = {k};
    g.target = c.target_stress;
    g.max_speed = c.speed;
    WallMotion m;
    m.velocity = c.speed * g.inward;
    sim.walls[k].start_motion(m, sim.time);
    servos.push_back(g);
  }
  // Each wall's stress is its force over its area inside the container now (walls/container.hpp).
  auto stress = [&]() {
    update_areas(sim, servos);
    const std::vector<WallLoad> f = sim.wall_loads();
    double s = 0;
    for (const ServoGroup& g : servos) s += g.stress(f);
    return s / servos.size();
  };
  const StartChecks checks(sim);
  checks.print("compact");
  double k_max = 0, c_max = 0;
  servo_constants(sim, k_max, c_max);
  const std::int64_t max_steps = static_cast<std::int64_t>(std::ceil(c.max_time / sim.dt));
  const std::int64_t check = c.settle.check_every.steps(sim.dt);
  Progress progress("compact", max_steps, o.quiet);
  std::int64_t steps = 0;
  bool done = false;
  checks.guard([&] {
  if (c.target_stress > 0) {
    // Stress servo (control/servo.hpp). Done when every wall is within 2 % of the target and the bed
    // is at rest (settle criterion).
    while (steps < max_steps && !done) {
      drive_servos(sim, servos, k_max, c_max);
      sim.advance();
      ++steps;
      progress.update(steps, sim.time);
      if (steps % check != 0) continue;
      update_areas(sim, servos);
      const std::vector<WallLoad> now = sim.wall_loads();
      bool within = true;
      for (const ServoGroup& g : servos) within = within && std::abs(g.stress(now) / c.target_stress - 1) <= 0.02;
      done = within && kinetic_ratio(sim) < c.settle.ke_ratio;
    }
  } else {
    // Porosity target: walls advance at `speed` until the bulk porosity reaches the target, then stop.
    while (steps < max_steps && !done) {
      sim.advance();
      ++steps;
      progress.update(steps, sim.time);
      done = porosity(sim) <= c.target_porosity;
    }
  }
  });
  progress.finish(steps, sim.time);
  if (!done) {
    std::ostringstream m;
    m << "compact: target not reached within compact.max_time = " << c.max_time << " s (stress " << stress()
      << " Pa, porosity " << porosity(sim) << ")";
    if (c.target_stress > 0) {  // which criterion held it back: each wall's stress, and the bed's motion
      const std::vector<WallLoad> now = sim.wall_loads();
      m << "; walls:";
      for (std::size_t k = 0; k < servos.size(); ++k)
        m << (k ? ", " : " ") << sim.walls[servos[k].elements[0]].name << " " << servos[k].stress(now) << " Pa";
      m << " (within 2 % of " << c.target_stress << " Pa needed), KE ratio " << kinetic_ratio(sim) << " (below compact.settle.ke_ratio = "
        << c.settle.ke_ratio << " needed)";
    }
    m << "; raise max_time or speed, or check the target";
    throw InputError(m.str());
  }
  for (const ServoGroup& g : servos) sim.walls[g.elements[0]].start_motion(WallMotion{}, sim.time);
  SettleResult s;
  if (c.target_porosity > 0) s = checks.guard([&] { return settle(sim, c.settle, "compact relax", o.quiet); });
  else s = {steps, kinetic_ratio(sim), true};
  write_checkpoint(o.out, sim, meta_for("compact", scene, o.in));
  if (c.target_stress > 0)
    std::printf("compact: moving-wall stress %.6g Pa (target %.6g Pa) after %lld servo steps\n", stress(), c.target_stress,
                static_cast<long long>(steps));
  else
    std::printf("compact: porosity %.6g after relaxation (target %.6g)\n", porosity(sim), c.target_porosity);
  report("compact", sim, s, seconds_since(t0));
}

}  // namespace dem
