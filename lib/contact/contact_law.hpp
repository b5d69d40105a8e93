#pragma once
// One contact law composed of independent parts (STYLE 2): an elastic normal law (normal_laws.hpp),
// viscous damping from restitution (eq. 2.27-2.29), an incremental tangential spring with radial
// return (eq. 2.13-2.16, 2.26) and the failure surface of fig. 2.13 with cohesion on bonded
// contacts. Stateless apart from the per-contact history passed in, so safe in any thread.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "contact/normal_laws.hpp"
#include "core/types.hpp"

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

template <class Normal>
struct ContactLaw {
  // `spring` is the stored tangential spring force on i (a global vector, SPEC §5 Decision),
  // rotated into the current tangent plane and updated in place; `bonded` is Φ, cleared when the
  // bond breaks.
  [[gnu::always_inline]] static ContactForce evaluate(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring, std::uint8_t& bonded) {
    spring = in_tangent_plane(spring, c.n);
    return evaluate_in_plane(p, c, dt, spring, bonded);
  }

  // The spring turned into the tangent plane of normal n, keeping its magnitude (the first part
  // of evaluate). Apart so that a force loop can turn the springs of many contacts before it
  // evaluates them: the division and square root here, and the ones that find n, then overlap
  // across contacts instead of each contact waiting for its own.
  [[gnu::always_inline]] static Vec3 in_tangent_plane(const Vec3& spring, const Vec3& n) {
    const double s2 = spring.squaredNorm();
    Vec3 s = spring - spring.dot(n) * n;
    if (s2 > 0) {
      const double t2 = s.squaredNorm();
      if (t2 > 0) s *= std::sqrt(s2 / t2);
    }
    return s;
  }

  // evaluate, for a spring already in the tangent plane (in_tangent_plane).
  [[gnu::always_inline]] static ContactForce evaluate_in_plane(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring,
                                                               std::uint8_t& bonded) {
    const Vec3& n = c.n;
    const double vn = c.v_rel.dot(n);  // > 0 when separating
    bool broken = false;
    const double f_el = Normal::elastic(p, c.overlap, bonded != 0, broken);
    if (broken) bonded = 0;
    // f_n = f_el + c_n du_n/dt with du_n/dt = -vn, eq. 2.27-2.28; not clipped (SPEC §6 Decision)
    // unless the pair asks for no_viscous_attraction (unbonded contacts only).
    const double sqrt_m = std::sqrt(c.m_eff);
    const double cn = p.damping_n * sqrt_m;  // 2 gamma_n sqrt(m* kn)
    double fn = f_el - cn * vn;
    if (!bonded && c.overlap <= 0) fn = 0;  // a pair apart whose bond just broke: no force
    if (p.no_viscous_attraction && !bonded) fn = std::max(fn, 0.0);

    // Tangential relative velocity at the contact point, eq. 2.12.
    const Vec3 vt = c.v_rel - vn * n - c.w_arm.cross(n);
    const Vec3 s = spring;  // in the tangent plane
    // Trial force (eq. 2.13-2.15): i is dragged along the motion of j relative to i.
    const Vec3 trial = s + p.kt * dt * vt;
    // Failure surface (fig. 2.13): Mohr-Coulomb with cohesion on bonded contacts, classic
    // Coulomb otherwise (SPEC §6 Decision). Tension is already capped at F by the normal law.
    const double tau = bonded ? std::max(0.0, p.cohesion + p.mu * fn) : p.mu * std::max(fn, 0.0);
    Vec3 ft;
    const double trial2 = trial.squaredNorm();
    if (trial2 <= tau * tau) {
      // The contact point's tangential motion has the effective mass 2/7 m* (solid spheres that
      // also spin: 1/m_t = 7/2 (1/m_i + 1/m_j)), so eq. 2.28 with m* would over-damp it by
      // sqrt(7/2) and make near-critical eta_t unstable in the explicit scheme.
      const double ct = p.damping_t * sqrt_m;  // 2 gamma_t sqrt(2/7 m* kt)
      spring = trial;
      ft = trial + ct * vt;  // sticking, damped
    } else {
      // Sliding: radial return onto the failure surface (eq. 2.26); the spring keeps tau.
      const double trial_norm = std::sqrt(trial2);
      spring = trial_norm > 0 ? Vec3(trial * (tau / trial_norm)) : Vec3::Zero();
      ft = spring;
    }
    return {-fn * n + ft, ft};
  }
};

}  // namespace dem
