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

// Whether a candidate touches now: the test that makes it a contact (with a bond, so does holding).
inline bool pair_touching(const Particles& p, int i, int j) {
  const double r = p.radius[i] + p.radius[j];
  return (p.x[j] - p.x[i]).squaredNorm() < r * r;
}
inline double wall_gap2(const Particles& p, const WallGeometry& g, int i, Vec3& to_wall) {
  to_wall = closest_point(g, p.x[i]) - p.x[i];
  return to_wall.squaredNorm();  // touching when < radius^2
}

// For every candidate of `pairs` and `walls`: decides whether it is a contact (`active`: touching,
// or holding by a bond), and if so fills .normal and .sum and updates its history; a candidate
// that is no contact gets a zero .sum and loses its spring. Returns the largest overlap relative
// to the smaller radius of its contact.
double compute_contact_forces(const ForceLoopInput& in, ForceVariant variant, ContactList& pairs, ContactList& walls);

}  // namespace dem
