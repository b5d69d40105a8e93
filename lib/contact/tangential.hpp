#pragma once
// The tangential sub-model of the contact law (contact/contact_law.hpp): an incremental spring
// with radial return (SPEC §5-6, eq. 2.13-2.16, 2.26) on the failure surface of fig. 2.13
// (Mohr-Coulomb with cohesion on bonded contacts, classic Coulomb otherwise, SPEC §6 Decision).
// Its history is the spring force on i, a global vector (SPEC §5 Decision), kept per contact.
//
// A tangential sub-model has: `keyword`; `keys` (its scene keys, contact/properties.hpp);
// `derive(p, properties)`; `in_tangent_plane(spring, n)` (its history turned into
// the current tangent plane); `force(p, vt, fn, bonded, dashpot, dt, spring, ft)` (over a lane type);
// `stored_energy(p, spring)`; `stiffness(p)` (for eq. 2.48).
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>

#include "contact/pair_params.hpp"
#include "contact/properties.hpp"
#include "simd/lanes.hpp"

namespace dem {

struct CoulombSpring {
  static constexpr std::string_view keyword = "coulomb";
  static constexpr PropertyKey keys[] = {
      {.keyword = "kt", .number = &ContactProperties::kt, .lo = 0, .hi = std::numeric_limits<double>::infinity(), .unit = "N/m",
       .si_unit = "N/m", .mixing = &MixingRules::stiffness, .default_key = "kn"},
      {.keyword = "friction_angle", .number = &ContactProperties::friction_angle, .lo = 0, .hi = 90, .hi_open = true,
       .unit = "degrees", .si_unit = "degree", .mixing = &MixingRules::friction},
      {.keyword = "cohesion", .number = &ContactProperties::cohesion, .lo = 0, .hi = std::numeric_limits<double>::infinity(),
       .unit = "N (C, bonded contacts)", .si_unit = "N", .mixing = &MixingRules::strength}};
  static void derive(PairParams& p, const PairProperties& pair) {
    const ContactProperties& q = pair.mixed;
    p.kt = q.kt;
    p.mu = std::tan(q.friction_angle * (std::numbers::pi / 180.0));
    p.cohesion = q.cohesion;
  }

  // The spring turned into the tangent plane of normal n, keeping its magnitude. Apart so that a
  // force loop can turn the springs of many contacts before it evaluates them: the division and
  // square root here, and the ones that find n, then overlap across contacts instead of each
  // contact waiting for its own.
  template <class L>
  [[gnu::always_inline]] static lanes::Triple<L> in_tangent_plane(const lanes::Triple<L>& spring, const lanes::Triple<L>& n) {
    using namespace lanes;
    const L zero(0.0);
    const L s2 = dot(spring, spring);
    const Triple<L> s = spring - dot(spring, n) * n;
    const L t2 = dot(s, s);
    return select(both(less(zero, s2), less(zero, t2)), s * root(s2 / t2), s);
  }

  // The tangential force `ft` on i for tangential velocity vt (eq. 2.12) and normal force fn (> 0
  // in compression), with dashpot coefficient c_t; `spring` (already in the tangent plane) is
  // updated in place. (An out-parameter: returned by value, the force was copied through the
  // stack in the four-wide law.)
  template <class P, class L, class M>
  [[gnu::always_inline]] static void force(const P& p, const lanes::Triple<L>& vt, const L& fn, const M& bonded, const L& dashpot,
                                           double dt, lanes::Triple<L>& spring, lanes::Triple<L>& ft) {
    using namespace lanes;
    const L zero(0.0);
    // Trial force (eq. 2.13-2.15): i is dragged along the motion of j relative to i.
    const Triple<L> trial = spring + (p.kt * L(dt)) * vt;
    // Failure surface (fig. 2.13). Tension is already capped at F by the normal law.
    const L cohesive = p.cohesion + p.mu * fn;
    const L tau = select(bonded, only_where(less(zero, cohesive), cohesive), p.mu * zero_where(less(fn, zero), fn));
    const L trial2 = dot(trial, trial);
    const M stick = less_or_equal(trial2, tau * tau);
    spring = trial;
    ft = trial + dashpot * vt;  // sticking, damped
    if (!all(stick)) {  // sliding: radial return onto the failure surface (eq. 2.26); the spring keeps tau
      const L trial_norm = root(trial2);
      const Triple<L> slid = only_where(less(zero, trial_norm), trial * (tau / trial_norm));
      spring = select(stick, spring, slid);
      ft = select(stick, ft, slid);
    }
  }

  // The energy held in the spring: |s|^2 / (2 kt) [J].
  static double stored_energy(const PairParams& p, const Vec3& spring) { return p.kt > 0 ? 0.5 * spring.squaredNorm() / p.kt : 0.0; }
  static double stiffness(const PairParams& p) { return p.kt; }
};

}  // namespace dem
