#pragma once
// The contact law: sub-models composed (ContactModel below), written once over a lane type
// (simd/lanes.hpp) for one contact or four at a time. Stateless apart from the per-contact
// history passed in, so safe in any thread.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "contact/damping.hpp"
#include "contact/kinematics.hpp"
#include "contact/normal_laws.hpp"
#include "contact/rolling.hpp"
#include "contact/tangential.hpp"
#include "core/types.hpp"
#include "simd/lanes.hpp"

namespace dem {

// A contact model composed of sub-models, each in its own file that owns everything about it: the
// elastic normal law (normal_laws.hpp) with its damping (damping.hpp), the tangential law with its
// dashpot and failure surface (tangential.hpp), the rolling resistance (rolling.hpp). The force
// loop is compiled for the combination a scene uses.
template <class Normal, class Tangential = CoulombSpring, class Rolling = NoRolling>
struct ContactModel {
  using NormalModel = Normal;
  using TangentialModel = Tangential;  // the four-wide loop turns springs with it
  using RollingModel = Rolling;
  using Damping = typename Normal::Damping;
  static constexpr bool has_rolling = !std::is_same_v<Rolling, NoRolling>;
  // Every sub-model written over lanes: the force loop also runs it four contacts at a time
  // (forces/pair_law_four_wide.hpp).
  static constexpr bool four_wide = Normal::four_wide && Tangential::four_wide && Rolling::four_wide;

  // The law for springs already in the tangent plane (Tangential::in_tangent_plane): `spring` and
  // `rolling` (the rolling law's history, if it keeps one) are updated in place, `bonded` (Phi)
  // cleared where the bond breaks.
  template <class L, class P, class M>
  [[gnu::always_inline]] static LaneForce<L> evaluate_in_plane(const P& p, const LaneKinematics<L>& c, double dt,
                                                                lanes::Triple<L>& spring, M& bonded, L& mark, lanes::Triple<L>& rolling) {
    using namespace lanes;
    const L zero(0.0);
    const Triple<L>& n = c.n;
    const L vn = dot(c.v_rel, n);  // > 0 when separating
    const L f_el = Normal::elastic(p, c.overlap, c.r_eff, bonded);  // clears bonded where the bond breaks
    // f_n = f_el + c_n du_n/dt, eq. 2.27-2.28, du_n/dt taken over the step (dashpot_force,
    // damping.hpp: second order, whatever the phase of the touch); not clipped (SPEC §6 Decision)
    // unless the pair asks for no_viscous_attraction (unbonded contacts only).
    const L c_t = Tangential::dashpot(p, c);  // beside the normal one: both read m*
    L fn = f_el;
    if constexpr (requires { Damping::force(p, c, vn, f_el, dt, bonded, mark); }) fn = fn + Damping::force(p, c, vn, f_el, dt, bonded, mark);  // mixed
    else fn = fn + dashpot_force<Damping>(p, c, vn, f_el, dt, bonded, mark);
    const auto apart = but_not(less_or_equal(c.overlap, zero), bonded);
    fn = zero_where(apart, fn);  // a pair apart whose bond just broke: no force
    mark = zero_where(apart, mark);
    fn = zero_where(both(but_not(p.no_viscous_attraction, bonded), less(fn, zero)), fn);
    // Tangential relative velocity at the contact point, eq. 2.12.
    const Triple<L> vt = (c.v_rel - vn * n) - cross(c.w_arm, n);
    LaneForce<L> f;
    const L k_t = Tangential::stiffness_at(p, c);  // the tangential spring's, read by the rolling law too
    Tangential::force(p, c, k_t, vt, fn, bonded, c_t, dt, spring, f.tangential);
    f.on_i = (-fn) * n + f.tangential;
    f.couple = Rolling::couple(p, c, f_el, k_t, dt, rolling);
    f.normal = fn, f.elastic = f_el;
    return f;
  }
  template <class L, class P, class M>
  [[gnu::always_inline]] static LaneForce<L> evaluate_in_plane(const P& p, const LaneKinematics<L>& c, double dt,
                                                                lanes::Triple<L>& spring, M& bonded, L& mark) {
    static_assert(!Rolling::has_history, "a rolling law with history needs its history passed");
    lanes::Triple<L> none{};
    return evaluate_in_plane(p, c, dt, spring, bonded, mark, none);
  }

  // One contact with Eigen's vectors, for the plain loops, the wall contacts and the tests.
  // `spring` and `rolling` are turned into the current tangent plane and updated in place;
  // `bonded` is Phi, cleared when the bond breaks; `mark` the dashpot's (dashpot_force).
  [[gnu::always_inline]] static ContactForce evaluate(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring,
                                                      std::uint8_t& bonded, double& mark, Vec3& rolling) {
    spring = in_tangent_plane(spring, c.n);
    if constexpr (Rolling::has_history) rolling = in_tangent_plane(rolling, c.n);
    return evaluate_in_plane(p, c, dt, spring, bonded, mark, rolling);
  }
  [[gnu::always_inline]] static ContactForce evaluate(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring,
                                                      std::uint8_t& bonded, double& mark) {
    Vec3 none = Vec3::Zero();
    return evaluate(p, c, dt, spring, bonded, mark, none);
  }
  // A contact without dashpot history (the tests of a law's force at one instant).
  [[gnu::always_inline]] static ContactForce evaluate(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring,
                                                      std::uint8_t& bonded) {
    double mark = 0;
    return evaluate(p, c, dt, spring, bonded, mark);
  }
  [[gnu::always_inline]] static Vec3 in_tangent_plane(const Vec3& spring, const Vec3& n) {
    return lanes::vec3(Tangential::in_tangent_plane(lanes::triple(spring), lanes::triple(n)));
  }
  [[gnu::always_inline]] static ContactForce evaluate_in_plane(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring,
                                                               std::uint8_t& bonded, double& mark, Vec3& rolling) {
    const LaneKinematics<double> k = lane_kinematics<has_rolling>(c);
    lanes::Triple<double> s = lanes::triple(spring), r = lanes::triple(rolling);
    bool b = bonded != 0;
    const LaneForce<double> f = evaluate_in_plane(p, k, dt, s, b, mark, r);
    spring = lanes::vec3(s);
    if constexpr (Rolling::has_history) rolling = lanes::vec3(r);
    bonded = b;
    return {lanes::vec3(f.on_i), lanes::vec3(f.tangential), lanes::vec3(f.couple), f.normal, f.elastic};
  }
};

}  // namespace dem
