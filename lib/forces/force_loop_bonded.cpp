// The force loops of the thesis's bonded normal laws (liu, mendes).
#include "forces/block_forces.hpp"

namespace dem {

ForceLoopFn bonded_force_loop(ModelChoice m) { return force_loop_if<AnyTangential, LiuNormal, MendesNormal>(m); }

}  // namespace dem
