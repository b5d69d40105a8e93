#include "run/generate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <sstream>

#include "core/error.hpp"
#include "generation/fill.hpp"
#include "io/checkpoint.hpp"
#include "io/scene_parser.hpp"
#include "run/progress.hpp"
#include "run/settle.hpp"
#include "run/setup.hpp"

namespace dem {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Bulk porosity of the bed: 1 - solid volume / container volume, where the container is the walls'
// bounding box cut at the top of the highest sphere along the direction opposite to gravity
// (an open or half-empty box would otherwise count its empty headspace as pores).
double porosity(const Simulation& sim) {
  if (sim.walls.empty() || sim.particles.size() == 0) return 0;
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Wall& w : sim.walls)
    for (const Vec3& v : w.vertices_at(sim.time)) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  int up = 0;
  sim.params.gravity.cwiseAbs().maxCoeff(&up);
  const auto [plo, phi] = sphere_bounds(sim.particles);
  if (sim.params.gravity[up] < 0) hi[up] = std::min(hi[up], phi[up]);
  if (sim.params.gravity[up] > 0) lo[up] = std::max(lo[up], plo[up]);
  const double box = (hi - lo).prod();
  double solid = 0;
  for (double a : sim.particles.radius) solid += sphere_volume(a);
  return box > 0 ? 1 - solid / box : 0;
}

void report(const char* tool, const Simulation& sim, const SettleResult& s, double wall_seconds) {
  std::printf("%s: %zu particles, %lld steps of dt = %.4g s (t = %.4g s), settled: %s (KE ratio %.3g), porosity %.4f, "
              "coordination %.3f, %.2f s wall\n",
              tool, sim.particles.size(), static_cast<long long>(s.steps), sim.dt, sim.time, s.converged ? "yes" : "no (time cap)",
              s.ke_ratio, porosity(sim), coordination_number(sim), wall_seconds);
}

CheckpointMeta meta_for(const char* tool, const Scene& scene) {
  CheckpointMeta m;
  m.writer = tool;
  m.scene_path = scene.path;
  m.scene_text = scene.text;
  m.run.stage = tool;
  return m;
}

}  // namespace

void gen_primary(const GenerateOptions& o) {
  const auto t0 = Clock::now();
  const Scene scene = read_scene_file(o.scene);
  if (!scene.generation) throw InputError(o.scene + ": gen-primary needs a [generation] table");
  Simulation sim = simulation_from_scene(scene);
  std::mt19937_64 rng(scene.generation->seed);
  fill_random(sim, *scene.generation, rng);
  sim.dt = choose_time_step(sim, scene.simulation);
  const SettleResult s = settle(sim, scene.generation->settle, "gen-primary settle", o.quiet);
  write_checkpoint(o.out, sim, meta_for("gen-primary", scene));
  report("gen-primary", sim, s, seconds_since(t0));
}

void copy_settle(const GenerateOptions& o) {
  const auto t0 = Clock::now();
  const Scene scene = read_scene_file(o.scene);
  if (!scene.copy) throw InputError(o.scene + ": copy-settle needs a [copy] table");
  Simulation sim;
  CheckpointMeta in_meta;
  read_checkpoint(o.in, sim, in_meta);
  adopt_scene(sim, scene, WallPositions::FromScene);  // the tiled sample needs the scene's container
  const auto [lo, hi] = sphere_bounds(sim.particles);
  const Vec3 period = scene.copy->spacing.value_or(hi - lo);
  tile(sim, scene.copy->nx, scene.copy->ny, scene.copy->nz, period);
  sim.dt = choose_time_step(sim, scene.simulation);
  const SettleResult s = settle(sim, scene.copy->settle, "copy-settle", o.quiet);
  write_checkpoint(o.out, sim, meta_for("copy-settle", scene));
  report("copy-settle", sim, s, seconds_since(t0));
}

void compact(const GenerateOptions& o) {
  const auto t0 = Clock::now();
  const Scene scene = read_scene_file(o.scene);
  if (!scene.compact) throw InputError(o.scene + ": compact needs a [compact] table");
  const CompactSpec& c = *scene.compact;
  Simulation sim;
  CheckpointMeta in_meta;
  read_checkpoint(o.in, sim, in_meta);
  adopt_scene(sim, scene);
  sim.dt = choose_time_step(sim, scene.simulation);

  // Each named wall moves along its normal towards the particles' centroid.
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& x : sim.particles.x) centroid += x;
  centroid /= std::max<double>(1, sim.particles.size());
  std::vector<std::size_t> moving;
  std::vector<Vec3> inward;
  std::vector<double> area;
  for (std::size_t k = 0; k < sim.walls.size(); ++k) {
    bool match = false;
    for (const std::string& name : c.walls) match = match || wall_matches(sim.walls[k].name, name);
    if (!match) continue;
    const std::vector<Vec3> v = sim.walls[k].vertices_at(sim.time);
    Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
    double a = 0.5 * n.norm();
    if (v.size() == 4) a += 0.5 * (v[2] - v[0]).cross(v[3] - v[0]).norm();
    n.normalize();
    if (n.dot(centroid - v[0]) < 0) n = -n;
    WallMotion m;
    m.kind = WallMotion::Kind::Translate;
    m.velocity = c.speed * n;
    sim.walls[k].start_motion(m, sim.time);
    moving.push_back(k);
    inward.push_back(n);
    area.push_back(a);
  }
  auto stress = [&]() {
    const std::vector<Vec3> f = sim.wall_forces();
    double s = 0;
    for (std::size_t m = 0; m < moving.size(); ++m) s += -f[moving[m]].dot(inward[m]) / area[m];
    return s / moving.size();
  };
  const std::int64_t max_steps = static_cast<std::int64_t>(std::ceil(c.max_time / sim.dt));
  Progress progress("compact", max_steps, o.quiet);
  std::int64_t steps = 0;
  bool reached = false;
  while (steps < max_steps && !reached) {
    sim.advance();
    ++steps;
    progress.update(steps, sim.time);
    reached = c.target_stress > 0 ? stress() >= c.target_stress : porosity(sim) <= c.target_porosity;
  }
  progress.finish(steps, sim.time);
  if (!reached) {
    std::ostringstream m;
    m << "compact: target not reached within compact.max_time = " << c.max_time << " s (stress " << stress()
      << " Pa, porosity " << porosity(sim) << "); raise max_time or speed, or check the target";
    throw InputError(m.str());
  }
  for (std::size_t k : moving) sim.walls[k].start_motion(WallMotion{}, sim.time);
  const SettleResult s = settle(sim, c.settle, "compact relax", o.quiet);
  write_checkpoint(o.out, sim, meta_for("compact", scene));
  if (c.target_stress > 0)
    std::printf("compact: moving-wall stress %.6g Pa after relaxation (target %.6g Pa)\n", stress(), c.target_stress);
  else
    std::printf("compact: porosity %.6g after relaxation (target %.6g)\n", porosity(sim), c.target_porosity);
  report("compact", sim, s, seconds_since(t0));
}

}  // namespace dem
