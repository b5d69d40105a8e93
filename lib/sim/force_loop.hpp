#pragma once
// The force loop: forces of every contact this step, one loop per law combination (STYLE 3),
// chosen once per step outside the loops so that a scene pays only for what it uses.
#include <vector>

#include "contact/contact_list.hpp"
#include "state/materials.hpp"
#include "state/particles.hpp"
#include "walls/wall.hpp"

namespace dem {

class Simulation;

// What the force loop reads.
struct ForceLoopInput {
  const Particles& particles;
  const MaterialTable& materials;
  const std::vector<Wall>& walls;
  const std::vector<WallGeometry>& geometry;  // the walls now
  double dt;
};

// Which instantiation runs: "cundall" (also any law while no contact is bonded: without bonds
// liu and mendes act exactly as cundall), "liu", "mendes" or "mixed".
enum class ForceVariant { Cundall, Liu, Mendes, Mixed };
ForceVariant choose_force_variant(const Simulation& sim);
const char* variant_name(ForceVariant v);

// For every candidate of `pairs` and `walls`: decides whether it is a contact (`active`: touching,
// or holding by a bond), and if so fills .normal, .force, .tangential and updates its history;
// a candidate that is no contact loses its spring. Returns the largest overlap relative to the
// smaller radius of its contact.
double compute_contact_forces(const ForceLoopInput& in, ForceVariant variant, ContactList& pairs, ContactList& walls);

}  // namespace dem
