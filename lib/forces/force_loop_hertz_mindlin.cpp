// The force loops of Hertz-Mindlin: the Hertz normal law with the Mindlin tangential spring, any
// rolling law.
#include "forces/block_forces.hpp"

namespace dem {

ForceLoopFn hertz_mindlin_force_loop(ModelChoice m) { return force_loop_if<MindlinSpring, HertzNormal>(m); }

}  // namespace dem
