#include "sim/health.hpp"

#include <algorithm>

#include "forces/force_loop.hpp"

namespace dem {

std::size_t intact_bonds(const Simulation& sim) {
  std::size_t n = 0;
  for (const ContactList* c : {&sim.pair_contacts(), &sim.wall_contacts()})
    for (std::size_t k = 0; k < c->size(); ++k) n += c->active[k] && c->bonded[k];
  sim.release_contact_views();
  return n;
}

Health measure_health(const Simulation& sim) {
  const Particles& p = sim.particles;
  Health h;
  const std::vector<std::size_t> by_id = p.slots_by_id();
  const MechanicalEnergy e = mechanical_energy(p, sim.params.gravity, sim.periodic, &by_id);
  h.kinetic_rotation = e.rotational;
  h.kinetic_translation = e.kinetic - e.rotational;
  h.particles = p.size();
  // The compacted lists: pairs in key order, wall contacts in the order of their keys too.
  const ContactList& pairs = sim.pair_contacts();
  const ContactList& walls = sim.wall_contacts();
  h.elastic_bound = stored_energy_bound(p, sim.materials, sim.walls, sim.wall_geometry(), sim.periodic, pairs, walls);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!pairs.active[k]) continue;
    ++h.pair_contacts;
    h.bonds += pairs.bonded[k];
    const int i = pairs.slot_i[k], j = pairs.slot_j[k];
    const double u = p.radius[i] + p.radius[j] - separation(p, sim.periodic, i, j).norm();
    h.max_overlap_ratio = std::max(h.max_overlap_ratio, u / std::min(p.radius[i], p.radius[j]));
  }
  for (std::size_t k = 0; k < walls.size(); ++k) {
    if (!walls.active[k]) continue;
    ++h.wall_contacts;
    h.bonds += walls.bonded[k];
    const int i = walls.slot_i[k];
    const double u = p.radius[i] - (closest_point(sim.wall_geometry()[walls.slot_j[k]], p.x[i]) - p.x[i]).norm();
    h.max_overlap_ratio = std::max(h.max_overlap_ratio, u / p.radius[i]);
  }
  h.coordination = h.particles ? 2.0 * static_cast<double>(h.pair_contacts) / static_cast<double>(h.particles) : 0.0;
  h.wall_loads = sim.wall_loads();
  // A long run should not carry a second copy of its contacts from one row to the next.
  sim.release_contact_views();
  return h;
}

}  // namespace dem
