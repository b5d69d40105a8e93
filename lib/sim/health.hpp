#pragma once
// The health of a run at the step just taken, as LIGGGHTS's thermo output gives it: kinetic energy
// (translation, rotation), elastic energy stored in the contacts, contact counts, coordination
// number, the largest overlap, intact bonds and the force on each wall element. run/health_log.hpp
// writes it every N steps as a CSV row and a console line.
//
// Every sum is taken in an order fixed by the particle ids or the contact keys, never by thread:
// the same state gives the same bits for any thread count.
#include <cstddef>
#include <vector>

#include "sim/simulation.hpp"

namespace dem {

struct Health {
  double kinetic_translation = 0;  // Σ ½ m v² [J] (v at the half step, as the energy check takes it)
  double kinetic_rotation = 0;     // Σ ½ I ω² [J]
  // Elastic energy in the active contacts [J] (stored_energy_bound, each law's own): exact for a
  // contact in compression and for the tangential spring; a bonded pair held in tension s counts
  // as F s, an upper bound of what it stores.
  double elastic_bound = 0;
  std::size_t particles = 0;
  std::size_t pair_contacts = 0;  // particle-particle contacts (touching, or held by an intact bond)
  std::size_t wall_contacts = 0;  // particle-wall contacts
  // Mean contacts per particle, 2 pair_contacts / particles: wall contacts are not counted, every
  // particle is (fixed ones and rattlers included). 0 without particles.
  double coordination = 0;
  // The largest overlap over the radius, the measure of simulation.max_overlap: a pair's overlap
  // over the smaller radius, a wall contact's over the particle's. 0 without overlap.
  double max_overlap_ratio = 0;
  std::size_t bonds = 0;  // intact bonds (Φ = 1), pair and wall contacts
  std::vector<WallLoad> wall_loads;  // per wall element (Simulation::wall_loads, no torque)
};

// Reads the contact lists of the last step (call it after Simulation::advance, not between a
// checkpoint read and the first step: the contacts' slots are found again by that step). Frees the
// compacted contact copies it makes (Simulation::release_contact_views).
Health measure_health(const Simulation& sim);

// Intact bonds (Φ = 1) among the contacts held now; valid before the first step too.
std::size_t intact_bonds(const Simulation& sim);

}  // namespace dem
