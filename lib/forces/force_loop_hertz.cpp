// The force loops of the Hertz normal law with the linear (coulomb) tangential spring, any rolling law.
#include "forces/block_forces.hpp"

namespace dem {

ForceLoopFn hertz_force_loop(ModelChoice m) { return force_loop_if<CoulombSpring, HertzNormal>(m); }

}  // namespace dem
