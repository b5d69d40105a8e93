// The force loop of scenes whose pairs of materials use different models: each contact's own
// (MixedModel, chosen per contact).
#include "forces/block_forces.hpp"

namespace dem {

ForceLoopFn mixed_force_loop() { return &all_forces<MixedModel>; }

}  // namespace dem
