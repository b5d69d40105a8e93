#pragma once
// The energy check of the unstable-run guard (simulation.max_energy_gain). Between a reference
// step and now, the particles' kinetic + potential energy can grow by no more than the elastic
// energy their contacts stored at the reference plus the work the walls did on them since: contact
// damping, friction, global damping and breaking bonds only take energy away. An explicit step too
// long for a contact's stiffness (eq. 2.48) creates energy at every contact it touches, so the
// excess grows with no bound, often long before an overlap or a NaN would stop the run.
//
// Kinetic energy is taken at the half step v^{n-1/2} and the potential energy at x^n; leapfrog's
// energy error is bounded and of order (ω Δt)² of the energy in motion, which the tolerance covers.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contact/contact_list.hpp"
#include "state/load_sum.hpp"
#include "state/materials.hpp"
#include "state/mechanical_energy.hpp"
#include "state/particles.hpp"
#include "state/periodic.hpp"
#include "walls/wall.hpp"

namespace dem {

// The particles' mechanical energy (state/mechanical_energy.hpp), summed over runs of `block`
// storage slots in parallel, then run by run (the same bits for any thread count). The runs follow
// `order` (a list of slots, e.g. Particles::slots_by_id: the same bits for any storage order) or,
// without it, the storage slots: the energy check, which only decides whether a run stops as
// unstable, takes that cheaper sum, over the force loop's blocks (SimParams::load_block), so that
// the force loop's own sum (ForceBlocks::energy_before_motion) has the same bits.
MechanicalEnergy mechanical_energy(const Particles& p, const Vec3& gravity, const PeriodicBox& box,
                                   const std::vector<std::size_t>* order = nullptr, long block = 1024);

// An upper bound on the elastic energy stored in the active contacts [J]: each normal law's own
// (contact/normal_laws.hpp: ½ kn u² in compression, F s for a bonded pair held in tension s), and
// ½ |f_s|²/kt in the tangential spring.
double stored_energy_bound(const Particles& p, const MaterialTable& materials, const std::vector<Wall>& walls,
                           const std::vector<WallGeometry>& geometry, const PeriodicBox& box, const ContactList& pairs,
                           const ContactList& wall_contacts);

// Power the prescribed particles (Particles::kPrescribed) deliver: what holds them to their motion
// cancels their net load (force and torque, gravity included), so it delivers
// -Σ (F·v + T·ω) over them [W].
double prescribed_power(const Particles& p, const LoadSum* force, const LoadSum* torque);

// The running balance kept by Simulation between a reference step and now.
struct EnergyBalance {
  bool valid = false;          // false: the next step takes a new reference
  std::int64_t step0 = 0;      // the reference step
  std::size_t particles = 0;   // particle count at the reference (a change re-takes it)
  MechanicalEnergy start;      // at the reference
  double stored0 = 0;          // stored_energy_bound at the reference [J]
  double potential_scale = 0;  // Σ m |g| a: one radius of fall for every particle [J]
  double wall_work = 0;        // ∫ (the walls' power + prescribed_power) dt since the reference [J]
  double wall_work_abs = 0;    // ∫ |that power| dt [J]
  MechanicalEnergy now;        // at the last check

  // Energy the particles hold beyond what they could have been given [J]; <= 0 in a sound run.
  double excess() const { return now.total() - start.total() - stored0 - wall_work; }
  // What the excess is compared with: the energy that has flowed through the system, plus one radius
  // of fall so that a bed at rest has a scale [J].
  double scale() const;
};

}  // namespace dem
