#include "run/health_log.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/output_paths.hpp"

namespace dem {

std::string health_path(const std::string& out) { return beside_output(out, ".health.csv"); }

std::int64_t health_interval(const Interval& cli, const Interval& scene, double stage_duration, double dt) {
  if (cli.given()) return cli.steps(dt);
  if (scene.given()) return scene.steps(dt);
  return std::max<std::int64_t>(kMinDefaultHealthEvery, std::llround(stage_duration / 100 / dt));
}

namespace {

std::string header(const WallGroups& groups) {
  std::string h =
      "step,time_s,dt_s,kinetic_translation_J,kinetic_rotation_J,elastic_bound_J,particles,pair_contacts,wall_contacts,coordination,"
      "max_overlap_per_radius,bonds,bonds_broken";
  for (const std::string& name : groups.names) h += ",force_" + name + "_N";
  return h + "\n";
}

}  // namespace

HealthLog::HealthLog(const std::string& path, const std::vector<Wall>& walls, std::int64_t every, std::int64_t total_steps,
                     std::int64_t resume_step, std::int64_t start_bonds, bool quiet)
    : csv_(path, header(wall_groups(walls)), "health log", resume_step),
      every_(every > 0 ? every : 1),
      total_(total_steps),
      start_bonds_(start_bonds),
      quiet_(quiet),
      tty_(isatty(fileno(stderr)) != 0),
      groups_(wall_groups(walls)) {}

void HealthLog::write(const Simulation& sim, std::int64_t steps_done) {
  const Health h = measure_health(sim);
  // Per wall (mesh elements summed), the magnitude of the total force the particles exert on it.
  std::vector<Vec3> force(groups_.names.size(), Vec3::Zero());
  for (std::size_t e = 0; e < h.wall_loads.size(); ++e) force[groups_.group_of[e]] += h.wall_loads[e].force;
  const long long broken = start_bonds_ >= 0 ? start_bonds_ - static_cast<long long>(h.bonds) : -1;
  std::FILE* f = csv_.file();
  if (f) {
    std::fprintf(f, "%lld,%.12g,%.10g,%.10g,%.10g,%.10g,%zu,%zu,%zu,%.10g,%.10g,%zu,", static_cast<long long>(sim.step), sim.time, sim.dt,
                 h.kinetic_translation, h.kinetic_rotation, h.elastic_bound, h.particles, h.pair_contacts, h.wall_contacts, h.coordination,
                 h.max_overlap_ratio, h.bonds);
    if (broken >= 0) std::fprintf(f, "%lld", broken);
    for (const Vec3& F : force) std::fprintf(f, ",%.10g", F.norm());
    std::fputc('\n', f);
    csv_.flush();
  }
  // The console line: the same figures, compact.
  char line[512];
  int n = std::snprintf(line, sizeof line, "health: t = %.6g s, step %lld/%lld, KE %.4g J (rot %.3g J), elastic <= %.4g J, contacts %zu + %zu wall, Z %.3f, overlap/r %.3g",
                        sim.time, static_cast<long long>(steps_done), static_cast<long long>(total_), h.kinetic_translation + h.kinetic_rotation,
                        h.kinetic_rotation, h.elastic_bound, h.pair_contacts, h.wall_contacts, h.coordination, h.max_overlap_ratio);
  if (start_bonds_ > 0 && n > 0 && n < static_cast<int>(sizeof line))
    n += std::snprintf(line + n, sizeof line - n, ", bonds %zu (%lld broken)", h.bonds, broken);
  if (!force.empty() && n > 0 && n < static_cast<int>(sizeof line)) {
    std::size_t top = 0;
    for (std::size_t g = 1; g < force.size(); ++g)
      if (force[g].norm() > force[top].norm()) top = g;
    std::snprintf(line + n, sizeof line - n, ", wall |F| max %.4g N (%s)", force[top].norm(), groups_.names[top].c_str());
  }
  last_line_ = line;
  if (!quiet_) {
    // Over a progress line on a terminal: clear it first (Progress draws it again).
    std::fprintf(stderr, "%s%s\n", tty_ ? "\r\033[K" : "", line);
    std::fflush(stderr);
  }
}

}  // namespace dem
