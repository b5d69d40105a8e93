#pragma once
// Fragments of a bonded assembly (docs/post.md, "Fragments"): the groups of particles joined by
// intact bonds, a particle with no intact bond being a fragment of its own. What an impact or a
// crushing test breaks a bonded block into, and the sizes a sieve would find.
#include <cstddef>
#include <vector>

#include "core/types.hpp"
#include "post/contact_forces.hpp"
#include "state/particles.hpp"

namespace dem {

struct Fragment {
  std::size_t particles = 0;
  double mass = 0;             // [kg]
  double volume = 0;           // the sum of its spheres' volumes [m³]
  Vec3 centre = Vec3::Zero();  // centre of mass, in stored coordinates (not unwrapped across periodic boundaries) [m]
  Index first_id = 0;          // its smallest particle id, which names it
  // The diameter of the sphere of the fragment's volume, (6 V / π)^(1/3) [m].
  double equivalent_diameter() const;
};

struct FragmentSet {
  std::vector<Fragment> fragments;  // largest mass first; equal masses by first_id
  std::vector<int> of_slot;         // the fragment (index into `fragments`) of each storage slot
  std::size_t intact_bonds = 0;     // bonded particle pairs (wall bonds join no particles)

  // The fraction of the total mass in fragments of equivalent diameter at most d: the passing
  // fraction of a sieve of aperture d.
  double mass_passing(double d) const;
};

// The fragments of particles `p` joined by the bonded pair contacts of `contacts` (whose pair_i,
// pair_j are storage slots of `p`). Linear in particles + contacts; the same result for any
// storage or contact order.
FragmentSet find_fragments(const Particles& p, const ContactForceSet& contacts);

}  // namespace dem
