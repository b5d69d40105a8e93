#pragma once
// One contact law composed of independent parts: an elastic normal law (normal_laws.hpp), viscous
// damping from restitution (eq. 2.27-2.29), an incremental tangential spring with radial return
// (eq. 2.13-2.16, 2.26) and the failure surface of fig. 2.13 with cohesion on bonded contacts.
// Written once over a lane type (simd/lanes.hpp), for one contact or four at a time. Stateless
// apart from the per-contact history passed in, so safe in any thread.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "contact/normal_laws.hpp"
#include "core/types.hpp"
#include "simd/lanes.hpp"

namespace dem {

// Relative kinematics of one contact, as seen from particle i (SPEC §5).
struct ContactKinematics {
  Vec3 n;          // unit normal from i to j (eq. 2.11 direction)
  double overlap;  // u_n > 0 in compression (eq. 2.11 / 2.17)
  Vec3 v_rel;      // v_j - v_i at the centres (wall: wall velocity - v_i)
  Vec3 w_arm;      // a_j w_j + a_i w_i (wall: a_i w_i), for eq. 2.12
  double m_eff;    // m_i m_j / (m_i + m_j), wall: m_i
};

struct ContactForce {
  Vec3 on_i;        // total force on i [N]; j receives the opposite (eq. 2.31-2.32)
  Vec3 tangential;  // tangential part of on_i, for the torques of eq. 2.33-2.34
};

// The law, written once over a lane type L (simd/lanes.hpp): one contact (L = double, from the
// plain loops and ContactLaw below) or four (L = Lanes4, sim/pair_law.cpp). `P` holds the pair
// constants by PairParams' names, as doubles or as lanes; `M` is L's mask type.
template <class L>
struct LaneKinematics {
  lanes::Triple<L> n;  // as ContactKinematics
  L overlap;
  lanes::Triple<L> v_rel, w_arm;
  L m_eff;
};
template <class L>
struct LaneForce {
  lanes::Triple<L> on_i, tangential;  // as ContactForce
};

// The spring turned into the tangent plane of normal n, keeping its magnitude (the first part of
// the law). Apart so that a force loop can turn the springs of many contacts before it evaluates
// them: the division and square root here, and the ones that find n, then overlap across contacts
// instead of each contact waiting for its own.
template <class L>
[[gnu::always_inline]] inline lanes::Triple<L> in_tangent_plane(const lanes::Triple<L>& spring, const lanes::Triple<L>& n) {
  using namespace lanes;
  const L zero(0.0);
  const L s2 = dot(spring, spring);
  const Triple<L> s = spring - dot(spring, n) * n;
  const L t2 = dot(s, s);
  return select(both(less(zero, s2), less(zero, t2)), s * root(s2 / t2), s);
}

// The law for a spring already in the tangent plane: `spring` (the stored tangential spring force on
// i, a global vector, SPEC §5 Decision) is updated in place, `bonded` (Φ) cleared where the bond
// breaks.
template <class Normal, class L, class P, class M>
[[gnu::always_inline]] inline LaneForce<L> evaluate_in_plane(const P& p, const LaneKinematics<L>& c, double dt,
                                                             lanes::Triple<L>& spring, M& bonded) {
  using namespace lanes;
  const L zero(0.0);
  const Triple<L>& n = c.n;
  const L vn = dot(c.v_rel, n);  // > 0 when separating
  const L f_el = Normal::elastic(p, c.overlap, bonded);  // clears bonded where the bond breaks
  // f_n = f_el + c_n du_n/dt with du_n/dt = -vn, eq. 2.27-2.28; not clipped (SPEC §6 Decision)
  // unless the pair asks for no_viscous_attraction (unbonded contacts only).
  const L sqrt_m = root(c.m_eff);
  L fn = f_el - (p.damping_n * sqrt_m) * vn;  // c_n = 2 gamma_n sqrt(m* kn)
  fn = zero_where(but_not(less_or_equal(c.overlap, zero), bonded), fn);  // a pair apart whose bond just broke: no force
  fn = zero_where(both(but_not(p.no_viscous_attraction, bonded), less(fn, zero)), fn);

  // Tangential relative velocity at the contact point, eq. 2.12.
  const Triple<L> vt = (c.v_rel - vn * n) - cross(c.w_arm, n);
  // Trial force (eq. 2.13-2.15): i is dragged along the motion of j relative to i.
  const Triple<L> trial = spring + (p.kt * L(dt)) * vt;
  // Failure surface (fig. 2.13): Mohr-Coulomb with cohesion on bonded contacts, classic Coulomb
  // otherwise (SPEC §6 Decision). Tension is already capped at F by the normal law.
  const L cohesive = p.cohesion + p.mu * fn;
  const L tau = select(bonded, only_where(less(zero, cohesive), cohesive), p.mu * zero_where(less(fn, zero), fn));
  const L trial2 = dot(trial, trial);
  const M stick = less_or_equal(trial2, tau * tau);
  // Sticking, damped. The contact point's tangential motion has the effective mass 2/7 m* (solid
  // spheres that also spin: 1/m_t = 7/2 (1/m_i + 1/m_j)), so eq. 2.28 with m* would over-damp it by
  // sqrt(7/2) and make near-critical eta_t unstable in the explicit scheme: c_t = 2 gamma_t
  // sqrt(2/7 m* kt).
  spring = trial;
  Triple<L> ft = trial + (p.damping_t * sqrt_m) * vt;
  if (!all(stick)) {  // sliding: radial return onto the failure surface (eq. 2.26); the spring keeps tau
    const L trial_norm = root(trial2);
    const Triple<L> slid = only_where(less(zero, trial_norm), trial * (tau / trial_norm));
    spring = select(stick, spring, slid);
    ft = select(stick, ft, slid);
  }
  return {(-fn) * n + ft, ft};
}

// One contact with Eigen's vectors, for the plain loops, the wall contacts and the tests.
template <class Normal>
struct ContactLaw {
  // `spring` is rotated into the current tangent plane and updated in place; `bonded` is Φ,
  // cleared when the bond breaks.
  [[gnu::always_inline]] static ContactForce evaluate(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring, std::uint8_t& bonded) {
    spring = in_tangent_plane(spring, c.n);
    return evaluate_in_plane(p, c, dt, spring, bonded);
  }
  [[gnu::always_inline]] static Vec3 in_tangent_plane(const Vec3& spring, const Vec3& n) {
    return lanes::vec3(dem::in_tangent_plane(lanes::triple(spring), lanes::triple(n)));
  }
  [[gnu::always_inline]] static ContactForce evaluate_in_plane(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring,
                                                               std::uint8_t& bonded) {
    const LaneKinematics<double> k{lanes::triple(c.n), c.overlap, lanes::triple(c.v_rel), lanes::triple(c.w_arm), c.m_eff};
    lanes::Triple<double> s = lanes::triple(spring);
    bool b = bonded != 0;
    const LaneForce<double> f = dem::evaluate_in_plane<Normal>(p, k, dt, s, b);
    spring = lanes::vec3(s);
    bonded = b;
    return {lanes::vec3(f.on_i), lanes::vec3(f.tangential)};
  }
};

}  // namespace dem
