#include "run/settle.hpp"

#include <cmath>

#include "core/error.hpp"
#include "run/progress.hpp"

namespace dem {

SettleResult settle(Simulation& sim, const SettleSpec& spec, const std::string& label, bool quiet) {
  SettleResult r;
  if (spec.max_time == 0) {  // the scene asks for no settling (e.g. a sphere placed to start at rest)
    r.skipped = true;
    return r;
  }
  if (!(sim.params.gravity.norm() > 0)) throw InputError("settling needs gravity: simulation.gravity is zero");
  if (sim.particles.size() == 0) return r;
  const std::int64_t max_steps = static_cast<std::int64_t>(std::ceil(spec.max_time / sim.dt));
  const std::int64_t check = spec.check_every.steps(sim.dt);
  Progress progress(label, max_steps, quiet);
  while (r.steps < max_steps) {
    sim.advance();
    ++r.steps;
    progress.update(r.steps, sim.time);
    if (r.steps % check == 0) {
      r.ke_ratio = kinetic_ratio(sim);
      if (r.ke_ratio < spec.ke_ratio) {
        r.converged = true;
        break;
      }
    }
  }
  r.ke_ratio = kinetic_ratio(sim);
  progress.finish(r.steps, sim.time);
  return r;
}

double kinetic_ratio(const Simulation& sim) {
  const Particles& p = sim.particles;
  if (p.size() == 0) return 0;
  double mass = 0, diameter = 0;
  for (std::size_t k = 0; k < p.size(); ++k) mass += p.mass[k], diameter += 2 * p.radius[k];
  const double n = static_cast<double>(p.size());
  const double scale = (mass / n) * sim.params.gravity.norm() * (diameter / n);
  return scale > 0 ? sim.kinetic_energy() / n / scale : 0;
}

double coordination_number(const Simulation& sim) {
  const double n = static_cast<double>(sim.particles.size());
  return n > 0 ? (2.0 * sim.pair_contact_count() + sim.wall_contact_count()) / n : 0.0;
}

}  // namespace dem
