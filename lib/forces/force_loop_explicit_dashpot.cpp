// The force loops with the explicit dashpot (docs/contact-laws.md eq. D7): Hertz-Mindlin with any
// rolling law, and cundall with the linear spring (force_loop_units.hpp, kCompiled).
#include "forces/block_forces.hpp"

namespace dem {

ForceLoopFn explicit_dashpot_force_loop(ModelChoice m) {
  return force_loop_if<AnyTangential, WithExplicitDashpot<HertzNormal>, WithExplicitDashpot<CundallNormal>>(m);
}

}  // namespace dem
