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
inline double damping_ratio(double eta) {
  const double l = std::log(eta);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

struct ViscousDamping {
  static constexpr std::string_view keyword = "viscous";
  // c_n = 2 gamma_n sqrt(m* kn) (eq. 2.28) [N s/m].
  template <class P, class L>
  [[gnu::always_inline]] static L coefficient(const P& p, const LaneKinematics<L>& c) {
    return p.damping_n * lanes::root(c.m_eff);
  }
  static constexpr PropertyKey keys[] = {
      {.keyword = "restitution", .number = &ContactProperties::restitution, .lo = 0, .hi = 1, .lo_open = true,
       .unit = "(eta_n, docs/physics.md eq. P14)", .si_unit = "1", .mixing = &MixingRules::restitution, .default_value = 1},
      {.keyword = "no_viscous_attraction", .flag = &ContactProperties::no_viscous_attraction}};
  static void derive(PairParams& p, const PairProperties& pair) {
    const ContactProperties& q = pair.mixed;
    p.no_viscous_attraction = q.no_viscous_attraction;
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
  template <class P, class L>
  [[gnu::always_inline]] static L coefficient(const P& p, const LaneKinematics<L>& c) {
    const L u = lanes::only_where(lanes::less(L(0.0), c.overlap), c.overlap);
    return p.hertz_damping * lanes::root(c.m_eff * lanes::root(c.r_eff * u));
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
