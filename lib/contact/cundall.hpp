#pragma once
// The `cundall` contact law (Cundall & Strack): linear spring-dashpot normal force, incremental
// tangential spring with Coulomb friction and radial return. A small value type: no state besides
// the per-contact history passed in (STYLE 1), so it is safe in any thread.
//
// How to write another law: give it the same `evaluate` signature, declare what history it needs,
// and add it to the registry in sim/force_loop.cpp.
#include <cmath>

#include "core/types.hpp"
#include "state/materials.hpp"

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

struct CundallLaw {
  // `spring` is the stored tangential spring force on i (global vector, SPEC §5 Decision); it is
  // rotated into the current tangent plane and updated in place.
  static ContactForce evaluate(const PairParams& p, const ContactKinematics& c, double dt, Vec3& spring) {
    const Vec3& n = c.n;
    const double vn = c.v_rel.dot(n);  // > 0 when separating
    // Normal: f_n = k_n u_n + c_n du_n/dt, du_n/dt = -vn; not clipped (SPEC §6 Decision).
    const double cn = 2.0 * p.gamma_n * std::sqrt(c.m_eff * p.kn);  // eq. 2.27-2.28
    const double fn = p.kn * c.overlap - cn * vn;

    // Tangential relative velocity at the contact point, eq. 2.12.
    const Vec3 vt = c.v_rel - vn * n - c.w_arm.cross(n);

    // Keep the spring in the current tangent plane, preserving its magnitude.
    const double s2 = spring.squaredNorm();
    Vec3 s = spring - spring.dot(n) * n;
    if (s2 > 0) {
      const double t2 = s.squaredNorm();
      if (t2 > 0) s *= std::sqrt(s2 / t2);
    }
    // Trial force (eq. 2.13-2.15): i is dragged along the motion of j relative to i.
    const Vec3 trial = s + p.kt * dt * vt;
    const double tau = p.mu * std::max(fn, 0.0);  // Coulomb, unbonded contact (SPEC §6 Decision)
    Vec3 ft;
    const double trial_norm = trial.norm();
    if (trial_norm <= tau) {
      const double ct = 2.0 * p.gamma_t * std::sqrt(c.m_eff * p.kt);
      spring = trial;
      ft = trial + ct * vt;  // sticking, damped
    } else {
      // Sliding: radial return onto the failure surface (eq. 2.26); the spring keeps tau.
      spring = trial_norm > 0 ? Vec3(trial * (tau / trial_norm)) : Vec3::Zero();
      ft = spring;
    }
    return {-fn * n + ft, ft};
  }
};

}  // namespace dem
