#pragma once
// Rolling resistance, a sub-model of the contact law (contact/contact_law.hpp): a couple that
// opposes the relative rotation of the two bodies about an axis in the tangent plane
// (docs/contact-laws.md eq. R1-R4). On i it is M, on j -M; it adds no force.
//
// A rolling sub-model has: `keyword`; `keys`; `derive(p, properties)`; `has_history` (whether it
// keeps a couple per contact, ContactList::rolling); `couple(p, c, f_el, k_t, dt, history)` (over a
// lane type: its couple on i for contact kinematics c, elastic normal force f_el and tangential
// stiffness k_t; `history`, already in the tangent plane, updated in place); `four_wide` (true:
// written over lanes);
// `stored_energy(p, history, k_t, r_eff)`; `stiffness(k_t)` (for eq. 2.48).
#include <array>
#include <cmath>
#include <limits>
#include <string_view>

#include "contact/kinematics.hpp"
#include "contact/pair_params.hpp"
#include "contact/properties.hpp"
#include "simd/lanes.hpp"

namespace dem {

// The relative rotation rate about the tangent plane's axes: w_rel less its part along n (eq. R1;
// the twist about n is not resisted).
template <class L>
[[gnu::always_inline]] inline lanes::Triple<L> rolling_rate(const LaneKinematics<L>& c) {
  return c.w_rel - lanes::dot(c.w_rel, c.n) * c.n;
}

inline constexpr PropertyKey kRollingFrictionKey = {.keyword = "rolling_friction", .number = &ContactProperties::rolling_friction,
                                                    .lo = 0, .hi = std::numeric_limits<double>::infinity(),
                                                    .unit = "(mu_r, eq. R2)", .si_unit = "1", .mixing = &MixingRules::friction, .required = true};

// No rolling resistance: only the tangential force turns the spheres.
struct NoRolling {
  static constexpr std::string_view keyword = "none";
  static constexpr std::array<PropertyKey, 0> keys{};
  static constexpr bool has_history = false;
  static constexpr bool four_wide = true;
  static void derive(PairParams&, const PairProperties&) {}
  template <class P, class L>
  [[gnu::always_inline]] static lanes::Triple<L> couple(const P&, const LaneKinematics<L>&, const L&, const L&, double,
                                                        lanes::Triple<L>&) {
    return {L(0.0), L(0.0), L(0.0)};
  }
  static double stored_energy(const PairParams&, const Vec3&, double, double) { return 0; }
  static double stiffness(double) { return 0; }
};

// Constant directional torque (CDT, Ai et al. 2011's model A; LIGGGHTS's `cdt`): a couple of the
// size the sphere needs to roll over the rolling resistance, mu_r R* f_el, against the rolling rate
// (eq. R2). Stateless; at rest its direction is undefined, so it is zero there (a sphere at rest on
// a plane may still jitter about the rest direction: Ai et al.'s known weakness of the model).
struct ConstantTorque {
  static constexpr std::string_view keyword = "cdt";
  static constexpr std::array<PropertyKey, 1> keys{kRollingFrictionKey};
  static constexpr bool has_history = false;
  static constexpr bool four_wide = true;
  static void derive(PairParams& p, const PairProperties& pair) { p.rolling_friction = pair.mixed.rolling_friction; }
  template <class P, class L>
  [[gnu::always_inline]] static lanes::Triple<L> couple(const P& p, const LaneKinematics<L>& c, const L& f_el, const L& /*k_t*/,
                                                        double /*dt*/, lanes::Triple<L>& /*history*/) {
    using namespace lanes;
    const Triple<L> w = rolling_rate(c);
    const L rate = root(dot(w, w));
    const L size = p.rolling_friction * c.r_eff * only_where(less(L(0.0), f_el), f_el);
    return only_where(less(L(0.0), rate), w * (-size / rate));
  }
  static double stored_energy(const PairParams&, const Vec3&, double, double) { return 0; }
  static double stiffness(double) { return 0; }
};

// Elastic-plastic spring (EPSD2: Ai et al. 2011's model C with Iwashita & Oda's stiffness, without
// its dashpot; LIGGGHTS's `epsd2`): an incremental rotational spring k_r = k_t R*^2 (eq. R3) kept
// per contact like the tangential spring, capped at the CDT couple mu_r R* f_el (eq. R4). Holds a
// sphere at rest on a slope below the rolling limit, where CDT jitters.
struct ElasticPlasticRolling {
  static constexpr std::string_view keyword = "epsd2";
  static constexpr std::array<PropertyKey, 1> keys{kRollingFrictionKey};
  static constexpr bool has_history = true;
  static constexpr bool four_wide = true;
  static void derive(PairParams& p, const PairProperties& pair) { p.rolling_friction = pair.mixed.rolling_friction; }
  template <class P, class L>
  [[gnu::always_inline]] static lanes::Triple<L> couple(const P& p, const LaneKinematics<L>& c, const L& f_el, const L& k_t, double dt,
                                                        lanes::Triple<L>& history) {
    using namespace lanes;
    const L zero(0.0);
    const L k_r = k_t * c.r_eff * c.r_eff;  // eq. R3
    const Triple<L> trial = history - (k_r * L(dt)) * rolling_rate(c);
    const L limit = p.rolling_friction * c.r_eff * only_where(less(zero, f_el), f_el);  // eq. R4
    const L trial2 = dot(trial, trial);
    const L trial_norm = root(trial2);
    history = select(less_or_equal(trial2, limit * limit), trial, only_where(less(zero, trial_norm), trial * (limit / trial_norm)));
    return history;
  }
  // |M|^2 / (2 k_r) [J].
  static double stored_energy(const PairParams&, const Vec3& history, double k_t, double r_eff) {
    const double k_r = k_t * r_eff * r_eff;
    return k_r > 0 ? 0.5 * history.squaredNorm() / k_r : 0.0;
  }
  // As a translational stiffness on a sphere of radius a >= R*: k_r / (I / m) <= k_t R*^2 / (2/5 a^2),
  // at most 5/2 k_t.
  static double stiffness(double k_t) { return 2.5 * k_t; }
};

}  // namespace dem
