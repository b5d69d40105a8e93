#include "run/energy_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/output_paths.hpp"

namespace dem {

std::string energy_path(const std::string& out) { return beside_output(out, ".energy.csv"); }

std::int64_t energy_interval(const Interval& cli, const Interval& scene, double dt) {
  return cli.given() ? cli.steps(dt) : scene.steps(dt);
}

namespace {

const char* const kHeader =
    "step,time_s,kinetic_translation_J,kinetic_rotation_J,potential_J,elastic_normal_J,elastic_tangential_J,elastic_rolling_J,"
    "elastic_fibres_J,damping_normal_J,friction_J,global_damping_J,rolling_J,bonds_released_J,fibres_released_J,work_walls_J,"
    "work_prescribed_J,work_fluid_J,inserted_J,balance_error_J,balance_error_relative\n";

}  // namespace

EnergyLog::EnergyLog(const std::string& path, std::int64_t every, std::int64_t resume_step)
    : csv_(every > 0 ? path : std::string(), kHeader, "energy log", resume_step), every_(every > 0 ? every : 1) {}

void EnergyLog::write(const Simulation& sim) {
  const EnergyLedger& l = sim.ledger;
  if (!l.have_reference) return;  // no step accounted yet
  const EnergyState& e = l.now;
  const EnergyTotals& t = l.totals;
  const double scale = l.scale();
  std::fprintf(csv_.file(),
               "%lld,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.6g,%.6g\n",
               static_cast<long long>(sim.step), sim.time, e.kinetic_translation, e.kinetic_rotation, e.potential, e.elastic_normal,
               e.elastic_tangential, e.elastic_rolling, e.elastic_fibres, t.damping_normal, l.friction(), t.global_damping, l.rolling(),
               t.released, t.fibres_released, t.work_walls, t.work_prescribed, t.work_fluid, t.inserted, l.error(),
               scale > 0 ? l.error() / scale : 0.0);
  csv_.flush();
}

}  // namespace dem
