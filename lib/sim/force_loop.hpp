#pragma once
// The force loop: forces of every contact this step, one loop per law combination (STYLE 3),
// chosen once per step outside the loops so that a scene pays only for what it uses.
#include <string>

namespace dem {

class Simulation;

// Which instantiation runs: "cundall" (also any law while no contact is bonded: without bonds
// liu and mendes act exactly as cundall), "liu", "mendes" or "mixed".
enum class ForceVariant { Cundall, Liu, Mendes, Mixed };
ForceVariant choose_force_variant(const Simulation& sim);
const char* variant_name(ForceVariant v);

// Fills pair_contacts / wall_contacts .normal, .force, .tangential and updates their history.
// Returns the largest overlap relative to the smaller radius of its contact.
double compute_contact_forces(Simulation& sim, ForceVariant variant);

}  // namespace dem
