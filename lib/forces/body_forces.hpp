#pragma once
// Body forces: loads that act on each particle alone, from its own state and the scene's fields.
// The force loop adds them to a particle's net load after its contacts (forces/force_loop.hpp
// ForceBlocks), in the order of the members below, so that the order of every sum is fixed.
// Gravity is the first; a new body force (fluid drag, say) is a member here and one more term in
// add_to, after those already there (docs/architecture.md).
#include "core/types.hpp"

namespace dem {

struct BodyForces {
  Vec3 gravity = Vec3::Zero();  // [m/s^2] (SimParams::gravity)

  // Adds the body forces on a particle of mass m to its force [N].
  void add_to(double mass, Vec3& force) const { force += mass * gravity; }
};

}  // namespace dem
