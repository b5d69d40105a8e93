#pragma once
// The combinations of contact models compiled as a force loop of their own, and the units that
// compile them (force_loop_<law>.cpp, each including block_forces.hpp): a parallel build compiles
// the units side by side. force_loop.cpp picks a unit's loop once per step.
#include <type_traits>

#include "contact/contact_law.hpp"
#include "contact/model_table.hpp"
#include "forces/force_loop.hpp"

namespace dem {

// One force loop: the forces of every contact this step for one model (block_forces.hpp's all_forces).
using ForceLoopFn = double (*)(const ForceLoopInput&, ContactList& pairs, ContactList& walls, ForceBlocks& loads);

// The combinations compiled as a force loop of their own (each one a full instantiation: compile
// time and code size); any other runs the per-contact choice ("mixed"). Every hertz combination;
// cundall with the linear spring and any rolling law; the bonded laws as the thesis has them; with
// the explicit dashpot (WithExplicitDashpot), the peers' usual models: Hertz-Mindlin with any
// rolling law, cundall with the linear spring alone.
template <class Normal, class Tangential, class Rolling>
constexpr bool kCompiled =
    std::is_same_v<Normal, HertzNormal> ||
    (std::is_same_v<Tangential, CoulombSpring> && (std::is_same_v<Normal, CundallNormal> || std::is_same_v<Rolling, NoRolling>));
template <class Normal, class Tangential, class Rolling>
constexpr bool kCompiled<WithExplicitDashpot<Normal>, Tangential, Rolling> =
    (std::is_same_v<Normal, HertzNormal> && std::is_same_v<Tangential, MindlinSpring>) ||
    (std::is_same_v<Normal, CundallNormal> && std::is_same_v<Tangential, CoulombSpring> && std::is_same_v<Rolling, NoRolling>);

using MixedModel = ContactModel<MixedNormal, MixedTangential, MixedRolling>;

// f(ContactModel<...>{}) for the models of `m` where compiled, f(MixedModel{}) otherwise.
template <class F>
decltype(auto) with_compiled_model(ModelChoice m, F&& f) {
  return with_normal_law(m.normal, [&](auto normal) {
    return with_tangential_law(m.tangential, [&](auto tangential) {
      return with_rolling_law(m.rolling, [&](auto rolling) {
        using N = std::remove_cvref_t<decltype(normal)>;
        using T = std::remove_cvref_t<decltype(tangential)>;
        using R = std::remove_cvref_t<decltype(rolling)>;
        using E = WithExplicitDashpot<N>;
        if (m.explicit_dashpot) {
          if constexpr (kCompiled<E, T, R>) return f(ContactModel<E, T, R>{});
          else return f(MixedModel{});
        }
        if constexpr (kCompiled<N, T, R>) return f(ContactModel<N, T, R>{});
        else return f(MixedModel{});
      });
    });
  });
}

// Whether the force loop compiles the models of `m` (kCompiled), else it runs the mixed loop.
inline bool is_compiled(ModelChoice m) {
  return with_compiled_model(m, [](auto model) { return !std::is_same_v<decltype(model), MixedModel>; });
}

// Each unit's loops: the one for `m` where that unit compiles it, else nullptr.
ForceLoopFn cundall_force_loop(ModelChoice m);        // force_loop_cundall.cpp
ForceLoopFn bonded_force_loop(ModelChoice m);         // force_loop_bonded.cpp: liu, mendes
ForceLoopFn hertz_force_loop(ModelChoice m);          // force_loop_hertz.cpp: hertz with coulomb
ForceLoopFn hertz_mindlin_force_loop(ModelChoice m);  // force_loop_hertz_mindlin.cpp
ForceLoopFn explicit_dashpot_force_loop(ModelChoice m);  // force_loop_explicit_dashpot.cpp
ForceLoopFn mixed_force_loop();                       // force_loop_mixed.cpp: MixedModel
// The units of the compiled combinations, asked in turn (compute_contact_forces).
inline constexpr ForceLoopFn (*kForceLoopUnits[])(ModelChoice) = {cundall_force_loop, bonded_force_loop, hertz_force_loop,
                                                                   hertz_mindlin_force_loop, explicit_dashpot_force_loop};

// set_lagging_thread_for_tests (force_loop.hpp): set between steps, read by the loops' threads.
struct LaggingThread {
  int thread = -1;
  int microseconds = 0;
};
extern LaggingThread lagging_thread;

}  // namespace dem
