#pragma once
// Viscous normal damping from restitution (SPEC §6, eq. 2.27-2.29), a sub-model of the contact law
// (contact/contact_law.hpp): the normal dashpot coefficient of one contact, c = 2 gamma sqrt(m k).
// It owns its constants (derive), and what a servo needs to bound a wall's response
// (largest_normal). The tangential dashpot is the tangential law's (tangential.hpp).
//
// A damping sub-model has: `keyword`; `keys` (its scene keys, contact/properties.hpp);
// `coefficient(p, c)` (its normal dashpot for contact kinematics c, over a lane type);
// `derive(p, properties)` (after the normal law's: it reads its stiffness);
// `largest_normal(p, mass, stiffness)` (the largest normal coefficient against a particle of that
// mass, for a servo's response).
#include <cmath>
#include <numbers>
#include <string_view>

#include "contact/kinematics.hpp"
#include "contact/pair_params.hpp"
#include "contact/properties.hpp"
#include "simd/lanes.hpp"

namespace dem {

// gamma = -ln(eta) / sqrt(pi^2 + ln^2 eta), eq. 2.29 (Tsuji et al.): the restitution of the
// linear spring and dashpot, unclipped, is eta.
// eta = 0 (perfectly plastic): the limit, gamma = 1, critical damping.
inline double damping_ratio(double eta) {
  if (!(eta > 0)) return 1.0;
  const double l = std::log(eta);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

struct ViscousDamping {
  static constexpr std::string_view keyword = "viscous";
  // c_n = 2 gamma_n sqrt(m* kn) (eq. 2.28) [N s/m].
  static constexpr bool constant = true;  // c_n does not depend on the overlap
  template <class P, class L>
  [[gnu::always_inline]] static L coefficient(const P& p, const LaneKinematics<L>& c) {
    return p.damping_n * lanes::root(c.m_eff);
  }
  static constexpr PropertyKey keys[] = {
      {.keyword = "restitution", .number = &ContactProperties::restitution, .lo = 0, .hi = 1,
       .unit = "(eta_n, docs/physics.md eq. P14; 0: critical damping)", .si_unit = "1", .mixing = &MixingRules::restitution, .default_value = 1},
      {.keyword = "no_viscous_attraction", .flag = &ContactProperties::no_viscous_attraction},
      {.keyword = "explicit_dashpot", .flag = &ContactProperties::explicit_dashpot, .absent_means_off = true}};
  static void derive(PairParams& p, const PairProperties& pair) {
    const ContactProperties& q = pair.mixed;
    p.no_viscous_attraction = q.no_viscous_attraction;
    p.explicit_dashpot = q.explicit_dashpot;
    p.gamma_n = damping_ratio(q.restitution);
    p.damping_n = 2.0 * p.gamma_n * std::sqrt(p.kn);
  }
  static double largest_normal(const PairParams& p, double mass, double stiffness) {
    return 2 * p.gamma_n * std::sqrt(mass * stiffness);
  }
};

// The damping of the hertz law (Tsuji et al. 1992's form): a dashpot that grows with the contact,
// c_n = 2 zeta sqrt(m* k(u)), k(u) = 2 E* sqrt(R* u) the law's slope (docs/contact-laws.md eq. H6).
// Its restitution depends on zeta alone, not on the speed: zeta = sqrt(5/6) gamma(eta) (eq. H7,
// gamma of eq. 2.29) gives eta (tests/test_hertz.cpp integrates the impact: within 1e-5).
struct HertzDamping {
  static constexpr std::string_view keyword = "hertz_viscous";
  static constexpr bool constant = false;
  template <class P, class L>
  [[gnu::always_inline]] static L coefficient(const P& p, const LaneKinematics<L>& c) { return coefficient_at(p, c, c.overlap); }
  // c_n at overlap x (0 where x <= 0).
  template <class P, class L>
  [[gnu::always_inline]] static L coefficient_at(const P& p, const LaneKinematics<L>& c, const L& x) {
    return p.hertz_damping * root_mass_radius(c, contact_radius(x, c.r_eff));
  }
  // Its integral over the overlap from 0 to x, given c_x = c_n(x): c_n grows as u^(1/4), so
  // 4/5 x c_n(x) (eq. D6).
  template <class L>
  [[gnu::always_inline]] static L primitive(const L& x, const L& c_x) {
    return L(0.8) * lanes::only_where(lanes::less(L(0.0), x), x) * c_x;
  }
  static constexpr auto& keys = ViscousDamping::keys;
  static void derive(PairParams& p, const PairProperties& pair) {
    ViscousDamping::derive(p, pair);
    // eq. H7, with k(u) = 3/2 (4/3 E*) sqrt(R* u).
    p.hertz_damping = 2 * std::sqrt(5.0 / 6.0) * p.gamma_n * std::sqrt(1.5 * p.hertz_modulus);
  }
  static double largest_normal(const PairParams& p, double mass, double stiffness) {
    return 2 * std::sqrt(5.0 / 6.0) * p.gamma_n * std::sqrt(mass * stiffness);  // eq. H6-H7 at the bound
  }
};

}  // namespace dem

namespace dem {

// The normal dashpot over one step, for a damping sub-model D (docs/contact-laws.md, "The dashpot
// in time", eq. D1-D6). The force at step n stands for the impulse over the half steps around it;
// the dashpot's impulse there is the integral of c_n over the overlap while the spheres touch:
// c_n (M+ - M-) for a constant c_n, M- and M+ the overlap at the half steps before and after (the
// "marks", 0 where apart). M- is the mark this contact left at the last step (`mark`, history);
// M+ the overlap at the next half step, predicted from this contact's own force and solved
// implicitly (eq. D3: in a lasting contact the trapezoidal rule, second order in dt, stable for
// any c_n), or 0 where the spheres part before the next step (eq. D4: the last step takes the
// dashpot's whole remaining impulse, so a contact's dashpot impulses sum to zero whatever the
// phase of its first and last steps). In a sustained contact the marks telescope: the dashpot acts
// on the change of the prediction, and a contact at rest in a packing feels none (eq. D5). A
// c_n that grows with the overlap (hertz) integrates it (D::primitive), linearised about the
// prediction and solved twice (eq. D6). Returns the dashpot's force, > 0 repulsive (du/dt c_n),
// and leaves the new mark in `mark`. vn > 0 separating; bonded contacts (which may hold u < 0)
// always take D3, marks unclipped.
template <class D, class P, class L, class M>
[[gnu::always_inline]] inline L dashpot_force(const P& p, const LaneKinematics<L>& k, const L& vn, const L& f_el, double dt,
                                              const M& bonded, L& mark) {
  using namespace lanes;
  const L zero(0.0), one(1.0), h(dt), half_h(0.5 * dt);
  const L& u = k.overlap;
  const L inv_m = one / k.m_eff;
  // No mark (a new contact, or one read without history): the overlap at the last half step if the
  // spheres touched at the last step by the kinematics, else 0 (eq. D2). "Touched" asks for an
  // overlap u - |vn| dt > |vn| dt / 2 at the last step: a touch that fell on a step boundary
  // leaves the last step's overlap at round-off, on either side of zero, and may or may not have
  // been a contact there; taken as new, it gets the dashpot's whole impulse from zero.
  const M none = equal(mark, zero);  // one comparison: +0 and -0 alike, a NaN never
  const L before = select(none, only_where(either(bonded, less(L(-1.5) * h * vn, u)), u + half_h * vn), mark);
  const L free = vn + h * (f_el * inv_m);  // the relative normal velocity after the step without the dashpot
  // A parting contact's mark is kept as 1e-300, not 0: should the spheres still touch at the next
  // step (others pushed them), it says that this step took the dashpot's impulse up to here, so the
  // next one starts from M- = 0, not from the estimate of a contact without history (D2).
  const L parted(1e-300);
  // Where D3's M+ would part the spheres before the next step (which then would not take its share
  // -c M+): the M+ that leaves them touching by 1e-6 r at the next step, which then takes the rest.
  // The division only where a lane needs it (almost never): the divider is the law's bottleneck.
  const auto lasting = [&](const L& inside, const L& r, const L& a2) {
    const M keep = either(bonded, less_or_equal(a2 * inside, r));
    if (all(keep)) return inside;
    return select(keep, inside, (r / a2) * L(1 - 1e-6));
  };
  if constexpr (D::constant) {
    const L c_n = D::coefficient(p, k);
    const L beta = c_n * inv_m, a2 = h * beta;  // a2 = c_n dt / m*
    const L b = free - beta * before;           // the velocity after the step with M+ = 0
    const L r = u - h * b;                      // the overlap at the next step then
    const L inside = (u - half_h * b) / (one + L(0.5) * a2);  // eq. D3
    const L ahead = select(but_not(less_or_equal(r, zero), bonded), parted, lasting(inside, r, a2));
    mark = ahead;
    return c_n * (ahead - before) * L(1.0 / dt);
  } else {
    const L g_before = D::primitive(before, D::coefficient_at(p, k, before));
    const L r_part = u - h * (free - g_before * inv_m);  // the overlap at the next step with M+ = 0
    L x = u, c_x = D::coefficient(p, k), ahead = u, impulse = zero;  // c_n at u: the contact's own roots (kinematics.hpp)
    for (int pass = 0; pass < 2; ++pass) {  // eq. D6: the integral linearised about x, first u, then the prediction
      if (pass > 0) c_x = D::coefficient_at(p, k, x);
      const L g_x = D::primitive(x, c_x);
      const L a2 = h * (c_x * inv_m);
      const L b = free + (g_x - g_before - c_x * x) * inv_m;
      const L r = u - h * b;
      ahead = lasting((u - half_h * b) / (one + L(0.5) * a2), r, a2);
      impulse = c_x * (ahead - x) + (g_x - g_before);
      x = select(less(zero, ahead), ahead, u);
    }
    const M parts = but_not(less_or_equal(r_part, zero), bonded);
    mark = select(parts, parted, ahead);
    return select(parts, zero - g_before, impulse) * L(1.0 / dt);
  }
}

// A damping sub-model D with the explicit dashpot of LIGGGHTS and LAMMPS in place of D1-D6: c_n(u)
// at this step's overlap times the last half step's relative normal velocity (docs/contact-laws.md
// eq. D7), first order in dt; it keeps no mark (left 0). The contact law takes a damping's own
// `force` where it has one (contact/contact_law.hpp).
template <class D>
struct ExplicitDashpot : D {
  template <class P, class L, class M>
  [[gnu::always_inline]] static L force(const P& p, const LaneKinematics<L>& k, const L& vn, const L& /*f_el*/, double /*dt*/,
                                        const M& /*bonded*/, L& mark) {
    mark = L(0.0);
    return L(0.0) - D::coefficient(p, k) * vn;  // eq. D7, > 0 repulsive
  }
};

}  // namespace dem
