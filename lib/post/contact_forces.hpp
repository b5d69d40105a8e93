#pragma once
// The contact forces of a state, as the post-processing reads them: one record per contact with
// the storage slots of its particles, the force, the normal and (wall contacts) the contact point.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/types.hpp"
#include "sim/simulation.hpp"

namespace dem {

struct ContactForceSet {
  // Particle pairs: i < j by id; `force` acts on i (j receives the opposite), `normal` points from
  // i to j (SPEC §5), so the normal force f_n = -force . normal is positive in compression.
  std::vector<int> pair_i, pair_j;
  std::vector<Vec3> pair_force, pair_normal;
  std::vector<std::uint8_t> pair_bonded;
  // Particle-wall contacts: particle slot, wall index, force on the particle, normal from the
  // particle towards the wall, and the contact point: the wall's closest point to the centre
  // (eq. 2.4-2.5), where the wall's force acts.
  std::vector<int> wall_i, wall_index;
  std::vector<Vec3> wall_force, wall_normal, wall_point;
  std::vector<std::uint8_t> wall_bonded;
  PeriodicBox periodic;  // the state's periodic boundaries, if any

  std::size_t pairs() const { return pair_i.size(); }
  // The branch vector of pair k, from i's centre to j's (to j's nearest image across a periodic
  // boundary) [m].
  Vec3 branch(const Particles& p, std::size_t k) const {
    return periodic.nearest(p.x[pair_j[k]] - p.x[pair_i[k]]);
  }
  std::size_t walls() const { return wall_i.size(); }
};

// The records of the last force evaluation of `sim` (pair_contacts(), wall_contacts()), with the
// wall contact points taken on wall_geometry() at the particles' positions `x` (the positions the
// forces were computed at). Throws std::logic_error where that step did not keep the pair
// contacts' forces (SimParams::keep_pair_results).
ContactForceSet contact_forces(const Simulation& sim, const std::vector<Vec3>& x);

// The forces at the state as it stands (a checkpoint keeps the contact history, not the forces):
// those the next step computes at x^n from v^{n-1/2} and the stored springs, by
// Simulation::compute_forces on a copy of `sim` (no step is taken); `sim` is unchanged. Throws PhysicsError where the
// state is unstable (an overlap beyond simulation.max_overlap).
ContactForceSet contact_forces_at_state(const Simulation& sim);

}  // namespace dem
