#pragma once
// Stage entries that act on a group of particles chosen by material, id range and region
// (scene/scene.hpp ParticleGroupSpec): `[[stage.set_velocity]]`, a velocity given once at the
// stage start, and `[[stage.prescribe]]`, a velocity kept for the whole stage whatever the forces
// (Particles::kPrescribed: the integrator moves such a particle at its own v and w).
#include <cstddef>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace dem {

// The storage slots of the particles in the group now, in storage order.
std::vector<std::size_t> select_group(const Simulation& sim, const ParticleGroupSpec& group);

// v (and w where given) of every particle of the group. Returns how many it set. A held particle
// (stage action `fix`) keeps its rest.
std::size_t set_group_velocity(Simulation& sim, const VelocitySpec& spec);

// Marks the group prescribed, with v and w (zero unless given), from now on. Returns how many.
std::size_t start_prescribed(Simulation& sim, const VelocitySpec& spec);

// The end of a stage that prescribed: its prescribed particles become free, moving on at the
// velocity they had. Returns how many.
std::size_t end_prescribed(Simulation& sim);

// What the rest of the system (contacts, walls) exerts on the prescribed particles this step: the
// sum of their net loads less their weight [N]. Only after a step (Simulation::net_force).
Vec3 force_on_prescribed(const Simulation& sim);

// How a group is named in messages: "material "B2", ids 0 to 9, inside the region".
std::string describe_group(const Simulation& sim, const ParticleGroupSpec& group);

}  // namespace dem
