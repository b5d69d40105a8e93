// The force loops of the linear (cundall) normal law: with the linear spring, any rolling law.
#include "forces/block_forces.hpp"

namespace dem {

ForceLoopFn cundall_force_loop(ModelChoice m) { return force_loop_if<AnyTangential, CundallNormal>(m); }

}  // namespace dem
