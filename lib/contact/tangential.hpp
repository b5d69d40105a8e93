#pragma once
// The tangential sub-models of the contact law (contact/contact_law.hpp): an incremental spring
// with radial return (SPEC §5-6, eq. 2.13-2.16, 2.26) on the failure surface of fig. 2.13
// (Mohr-Coulomb with cohesion on bonded contacts, classic Coulomb otherwise, SPEC §6 Decision),
// whose stiffness is a constant (CoulombSpring) or grows with the contact radius (MindlinSpring).
// Its history is the spring force on i, a global vector (SPEC §5 Decision), kept per contact.
//
// A tangential sub-model has: `keyword`; `keys` (its scene keys, contact/properties.hpp); `four_wide`
// (true: written over lanes);
// `derive(p, properties)`; `in_tangent_plane(spring, n)` (its history turned into the current
// tangent plane); `dashpot(p, c)` (its coefficient c_t for contact kinematics c);
// `force(p, c, k_t, vt, fn, bonded, dashpot, dt, spring, ft)` (over a lane type; k_t its
// stiffness_at this contact);
// `stored_energy(p, spring, u, r_eff)`; `stiffness(p, scale)` (for eq. 2.48); `stiffness_at(p, c)` (its
// stiffness at one contact, which a rolling law reads).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>

#include "contact/damping.hpp"
#include "contact/kinematics.hpp"
#include "contact/pair_params.hpp"
#include "contact/properties.hpp"
#include "simd/lanes.hpp"

namespace dem {

// What every tangential spring shares: its history turned with the contact, and the step of eq.
// 2.13-2.16 and 2.26 for a given stiffness.
struct TangentialSpring {
  static constexpr bool four_wide = true;  // written over lanes (a mixed choice per contact is not)
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
  // in compression), with spring stiffness k and dashpot coefficient c_t; `spring` (already in the
  // tangent plane) is updated in place. (An out-parameter: returned by value, the force was copied
  // through the stack in the four-wide law.)
  template <class P, class L, class M>
  [[gnu::always_inline]] static void step(const P& p, const L& k, const lanes::Triple<L>& vt, const L& fn, const M& bonded,
                                          const L& dashpot, double dt, lanes::Triple<L>& spring, lanes::Triple<L>& ft) {
    using namespace lanes;
    const L zero(0.0);
    // Trial force (eq. 2.13-2.15): i is dragged along the motion of j relative to i.
    const Triple<L> trial = spring + (k * L(dt)) * vt;
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

  static constexpr PropertyKey kFrictionAngleKey = {.keyword = "friction_angle", .number = &ContactProperties::friction_angle, .lo = 0,
                                                    .hi = 90, .hi_open = true, .unit = "degrees", .si_unit = "degree",
                                                    .mixing = &MixingRules::friction};
  static constexpr PropertyKey kCohesionKey = {.keyword = "cohesion", .number = &ContactProperties::cohesion, .lo = 0,
                                               .hi = std::numeric_limits<double>::infinity(), .unit = "N (C, bonded contacts)",
                                               .si_unit = "N", .mixing = &MixingRules::strength};
  static constexpr PropertyKey kRestitutionKey = {.keyword = "tangential_restitution", .number = &ContactProperties::restitution_t,
                                                  .lo = 0, .hi = 1, .unit = "(eta_t, docs/physics.md eq. P14; 0: critical damping)", .si_unit = "1",
                                                  .mixing = &MixingRules::restitution, .default_key = "restitution"};
  // The friction and cohesion of the failure surface.
  static void derive_surface(PairParams& p, const ContactProperties& q) {
    p.mu = std::tan(q.friction_angle * (std::numbers::pi / 180.0));
    p.cohesion = q.cohesion;
    p.gamma_t = damping_ratio(q.restitution_t);
  }
};

// A linear spring kt (eq. 2.13-2.16) with a linear dashpot.
struct CoulombSpring : TangentialSpring {
  static constexpr std::string_view keyword = "coulomb";
  static constexpr PropertyKey keys[] = {
      {.keyword = "kt", .number = &ContactProperties::kt, .lo = 0, .hi = std::numeric_limits<double>::infinity(), .unit = "N/m",
       .si_unit = "N/m", .mixing = &MixingRules::stiffness, .default_key = "kn"},
      kFrictionAngleKey, kCohesionKey, kRestitutionKey};
  static void derive(PairParams& p, const PairProperties& pair) {
    p.kt = pair.mixed.kt;
    derive_surface(p, pair.mixed);
    // eq. 2.28 with the effective mass 2/7 m* of the contact point (spheres that also spin:
    // 1/m_t = 7/2 (1/m_i + 1/m_j)): m* would over-damp it by sqrt(7/2) and make near-critical
    // eta_t unstable in the explicit scheme.
    p.damping_t = 2.0 * p.gamma_t * std::sqrt(2.0 / 7.0 * p.kt);
  }
  template <class P, class L>
  [[gnu::always_inline]] static L dashpot(const P& p, const LaneKinematics<L>& c) {
    return p.damping_t * lanes::root(c.m_eff);
  }
  // The spring's stiffness at this contact [N/m].
  template <class P, class L>
  [[gnu::always_inline]] static L stiffness_at(const P& p, const LaneKinematics<L>& /*c*/) {
    return L(p.kt);
  }
  template <class P, class L, class M>
  [[gnu::always_inline]] static void force(const P& p, const LaneKinematics<L>& /*c*/, const L& k_t, const lanes::Triple<L>& vt,
                                           const L& fn, const M& bonded, const L& dashpot, double dt, lanes::Triple<L>& spring,
                                           lanes::Triple<L>& ft) {
    step(p, k_t, vt, fn, bonded, dashpot, dt, spring, ft);
  }
  // The energy held in the spring: |s|^2 / (2 kt) [J].
  static double stored_energy(const PairParams& p, const Vec3& spring, double /*u*/, double /*r_eff*/) {
    return p.kt > 0 ? 0.5 * spring.squaredNorm() / p.kt : 0.0;
  }
  static double stiffness(const PairParams& p, const ContactScale& /*scale*/) { return p.kt; }
};

// Mindlin's no-slip spring of elastic spheres (docs/contact-laws.md eq. H8-H10), the tangential
// part of Hertz-Mindlin: the stiffness k_t = 8 G* a grows with the contact radius a = sqrt(R* u),
// 1/G* = (2 - nu_a)/G_a + (2 - nu_b)/G_b with G = E / (2 (1 + nu)). Incremental, as the linear
// spring: the force changes by k_t(u) times the tangential displacement of the step; while the
// contact unloads, the force held is first scaled by a / a_old (Mindlin & Deresiewicz's unloading,
// as Thornton et al. 2011 and LAMMPS's mindlin_rescale/force: without it an impact that sticks
// gains energy). a_old comes from the last step's overlap u + v_n dt (positions advance by the
// velocities the force loop sees), so the law keeps no history beyond the spring. The Coulomb
// limit and radial return are the linear spring's. Its dashpot grows as the hertz one:
// c_t = 2 zeta_t sqrt(2/7 m* k_t(u)), zeta_t = sqrt(5/6) gamma(eta_t).
struct MindlinSpring : TangentialSpring {
  static constexpr std::string_view keyword = "mindlin";
  static constexpr PropertyKey keys[] = {kYoungModulusKey, kPoissonRatioKey, kFrictionAngleKey, kCohesionKey, kRestitutionKey};
  static void derive(PairParams& p, const PairProperties& pair) {
    derive_surface(p, pair.mixed);
    const auto compliance = [](const ContactProperties& m) {
      const double shear_modulus = m.young_modulus / (2 * (1 + m.poisson_ratio));
      return (2 - m.poisson_ratio) / shear_modulus;
    };
    p.mindlin_modulus = 8.0 / (compliance(pair.a) + compliance(pair.b));  // eq. H9
    p.mindlin_damping = 2 * std::sqrt(5.0 / 6.0) * p.gamma_t * std::sqrt(2.0 / 7.0 * p.mindlin_modulus);  // eq. H10
    p.kt = 0;  // no linear spring
  }
  // c_t with the contact radius a = sqrt(R* u) (kinematics.hpp: the hertz law's and its dashpot's).
  template <class P, class L>
  [[gnu::always_inline]] static L dashpot(const P& p, const LaneKinematics<L>& c) {
    return p.mindlin_damping * root_mass_radius(c, contact_radius(c));
  }
  // k_t = 8 G* a (eq. H8) [N/m].
  template <class P, class L>
  [[gnu::always_inline]] static L stiffness_at(const P& p, const LaneKinematics<L>& c) {
    return p.mindlin_modulus * contact_radius(c);
  }
  template <class P, class L, class M>
  [[gnu::always_inline]] static void force(const P& p, const LaneKinematics<L>& c, const L& k_t, const lanes::Triple<L>& vt,
                                           const L& fn, const M& bonded, const L& dashpot, double dt, lanes::Triple<L>& spring,
                                           lanes::Triple<L>& ft) {
    using namespace lanes;
    // Unloading (eq. H11): u_old = u + v_n dt > u scales the spring by a / a_old = sqrt(u / u_old).
    const L zero(0.0);
    const L u = only_where(less(zero, c.overlap), c.overlap);
    const L u_old = u + dot(c.v_rel, c.n) * L(dt);
    spring = select(less(u, u_old), spring * root(u / u_old), spring);
    step(p, k_t, vt, fn, bonded, dashpot, dt, spring, ft);
  }
  // |s|^2 / (2 k_t(u)) [J]: the energy of the spring at the current stiffness.
  static double stored_energy(const PairParams& p, const Vec3& spring, double u, double r_eff) {
    const double k = p.mindlin_modulus * contact_radius(u, r_eff);
    return k > 0 ? 0.5 * spring.squaredNorm() / k : 0.0;
  }
  // k_t at the largest radius and overlap a run reaches (as the hertz normal law's bound).
  static double stiffness(const PairParams& p, const ContactScale& scale) {
    return p.mindlin_modulus * std::sqrt(scale.radius * scale.overlap);
  }
};

}  // namespace dem
