#include "post/contact_forces.hpp"

#include <stdexcept>

namespace dem {

ContactForceSet contact_forces(const Simulation& sim, const std::vector<Vec3>& x) {
  if (!sim.pair_results_kept())
    throw std::logic_error("contact_forces: the last step did not keep the pair contacts' forces (SimParams::keep_pair_results)");
  ContactForceSet s;
  s.periodic = sim.periodic;
  const ContactList& pc = sim.pair_contacts();
  s.pair_i.assign(pc.slot_i.begin(), pc.slot_i.end());
  s.pair_j.assign(pc.slot_j.begin(), pc.slot_j.end());
  s.pair_normal.assign(pc.normal.begin(), pc.normal.end());
  s.pair_bonded.assign(pc.bonded.begin(), pc.bonded.end());
  s.pair_force.resize(pc.size());
  for (std::size_t k = 0; k < pc.size(); ++k) s.pair_force[k] = pc.force(k);

  const ContactList& wc = sim.wall_contacts();
  const std::vector<WallGeometry>& geometry = sim.wall_geometry();
  s.wall_i.assign(wc.slot_i.begin(), wc.slot_i.end());
  s.wall_index.assign(wc.slot_j.begin(), wc.slot_j.end());
  s.wall_normal.assign(wc.normal.begin(), wc.normal.end());
  s.wall_bonded.assign(wc.bonded.begin(), wc.bonded.end());
  s.wall_force.resize(wc.size());
  s.wall_point.resize(wc.size());
  for (std::size_t k = 0; k < wc.size(); ++k) {
    s.wall_force[k] = wc.force(k);
    s.wall_point[k] = closest_point(geometry[wc.slot_j[k]], x[wc.slot_i[k]]);
  }
  return s;
}

ContactForceSet contact_forces_at_state(const Simulation& sim) {
  // A copy, since computing the forces moves its contact history on; the copy keeps the storage
  // order, so its slots index `sim`'s particles.
  Simulation probe = sim;
  probe.params.keep_pair_results = true;
  probe.compute_forces();
  return contact_forces(probe, sim.particles.x);
}

}  // namespace dem
