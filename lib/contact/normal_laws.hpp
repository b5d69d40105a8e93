#pragma once
// Elastic normal laws f_el(u_n) of SPEC §6, as small stateless types, each owning everything about
// itself: its scene keyword, its force, the elastic energy it stores (for the energy check,
// sim/energy_audit.hpp), its stiffness for the critical time step (eq. 2.48) and the constants it
// derives per material pair. u is the overlap (> 0 in compression); the force is positive when
// repulsive. `bonded` is the contact's bond flag Φ; a law clears it when the bond fails in this
// step (irreversible, SPEC §6 Decision).
//
// `Damping` is its damping sub-model (contact/damping.hpp). `WithoutBonds` is the law it acts as exactly while no contact of the scene is bonded (the force
// loop then runs that one: liu and mendes run the four-wide cundall code).
//
// Each law lists the scene keys it reads (`keys`, contact/properties.hpp) and derives its
// constants from them (`derive`).
//
// Each law is written over a lane type (simd/lanes.hpp), selections in place of branches: one
// source runs one contact at a time (L = double, P = PairParams) and four (four_wide; the per-pair
// choice of a mixed scene, MixedNormal in model_table.hpp, runs one at a time).
//
// How to add a law: a struct here with the members below, its entry in model_table.hpp (one
// enum value in contact/pair_params.hpp, one case), its tests, and its keyword in docs/scene.md.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "contact/damping.hpp"
#include "contact/kinematics.hpp"
#include "contact/pair_params.hpp"
#include "contact/properties.hpp"
#include "simd/lanes.hpp"

namespace dem {

// The scene keys the laws read (contact/properties.hpp).
inline constexpr PropertyKey kNormalStiffnessKey{.keyword = "kn", .number = &ContactProperties::kn, .lo = 0,
                                                 .hi = std::numeric_limits<double>::infinity(), .lo_open = true, .unit = "N/m",
                                                 .si_unit = "N/m", .mixing = &MixingRules::stiffness, .required = true};
inline constexpr PropertyKey kTensileStrengthKey{.keyword = "tensile_strength", .number = &ContactProperties::tensile_strength, .lo = 0,
                                                 .hi = std::numeric_limits<double>::infinity(), .unit = "N (F, bonded contacts)",
                                                 .si_unit = "N", .mixing = &MixingRules::strength};
inline constexpr PropertyKey kMendesEpsilonKey{.keyword = "epsilon", .number = &ContactProperties::epsilon, .lo = 0, .hi = 1,
                                               .lo_open = true, .hi_open = true, .unit = "(mendes law, docs/physics.md eq. P12)", .si_unit = "1",
                                               .mixing = &MixingRules::strength, .default_value = 1e-4};

// A bond of a law without tension (`mendes` with epsilon >= 1/e) breaks as soon as its particles
// separate (SPEC §6 Decision (separation): s0 = 0). "Separate" means a gap beyond round-off: up to
// this fraction of the effective diameter 2R* (at least the smaller radius of a pair; a wall
// contact: the sphere's diameter) the particles still touch, so that a touching lattice bonded by
// the stage action `bond` (whose default bond_gap is the same 1e-6, of the smaller radius) does not
// lose the bonds whose centres happen to lie a few ulps too far apart.
inline constexpr double kBondTouchTolerance = 1e-6;

// SPEC §6 Decision (separation), for the laws without tension (cundall, hertz, mendes with
// epsilon >= 1/e): the bond breaks where the particles are apart by more than
// kBondTouchTolerance 2R*. Written over lanes: the four-wide cundall code runs it too.
template <class L>
[[gnu::always_inline]] inline auto separated(const L& u, const L& r_eff) {
  return lanes::less(u, -(L(2 * kBondTouchTolerance) * r_eff));
}
template <class L, class M>
[[gnu::always_inline]] inline void break_when_apart(const L& u, const L& r_eff, M& bonded) {
  bonded = lanes::but_not(bonded, separated(u, r_eff));
}

// The energy bound of the linear compression every law shares: ½ kn u² [J].
inline double linear_compression_energy(const PairParams& p, double u) { return u > 0 ? 0.5 * p.kn * u * u : 0.0; }

// Cundall & Strack: linear in compression, no tension; a bond (cohesion C in shear) holds while
// the particles touch.
struct CundallNormal {
  using Damping = ViscousDamping;
  static constexpr std::string_view keyword = "cundall";
  static constexpr bool four_wide = true;
  using WithoutBonds = CundallNormal;  // the law it acts as while no contact is bonded
  template <class P, class L, class M>
  [[gnu::always_inline]] static L elastic(const P& p, const L& u, const L& r_eff, M& bonded) {
    break_when_apart(u, r_eff, bonded);
    return lanes::only_where(lanes::less(L(0.0), u), p.kn * u);
  }
  static double stored_energy(const PairParams& p, double u, double /*r_eff*/, bool /*bonded*/) { return linear_compression_energy(p, u); }
  // The elastic energy held exactly (the energy balance, docs/physics.md eq. P31): the same.
  static double elastic_energy(const PairParams& p, double u, double r_eff, bool bonded) { return stored_energy(p, u, r_eff, bonded); }
  static double stiffness(const PairParams& p, const ContactScale& /*scale*/) { return p.kn; }
  static constexpr PropertyKey keys[] = {kNormalStiffnessKey};
  static void derive(PairParams& p, const PairProperties& pair) {
    const ContactProperties& q = pair.mixed;
    p.kn = q.kn;
    p.break_separation = 0;
  }
};

// Liu (eq. 2.21): linear in compression and, while bonded, in tension up to the strength F; the
// bond breaks abruptly when the tension would exceed F.
struct LiuNormal {
  using Damping = ViscousDamping;
  static constexpr std::string_view keyword = "liu";
  static constexpr bool four_wide = true;
  using WithoutBonds = CundallNormal;  // its tension needs a bond
  template <class P, class L, class M>
  [[gnu::always_inline]] static L elastic(const P& p, const L& u, const L& /*r_eff*/, M& bonded) {
    using namespace lanes;
    const M compressed = less_or_equal(L(0.0), u);
    const L f = p.kn * u;
    bonded = but_not(bonded, but_not(less(p.tensile_strength, -f), compressed));  // tension beyond F breaks the bond (docs/physics.md P11)
    return only_where(either(compressed, bonded), f);
  }
  // A bonded pair held in tension s stores at most F s (the attraction never exceeds F).
  static double stored_energy(const PairParams& p, double u, double /*r_eff*/, bool bonded) {
    return u >= 0 ? linear_compression_energy(p, u) : bonded ? p.tensile_strength * -u : 0.0;
  }
  // Exactly: ½ kn u² on both sides while bonded (docs/physics.md eq. P31).
  static double elastic_energy(const PairParams& p, double u, double /*r_eff*/, bool bonded) {
    return u >= 0 || bonded ? 0.5 * p.kn * u * u : 0.0;
  }
  static double stiffness(const PairParams& p, const ContactScale& /*scale*/) { return p.kn; }
  static constexpr PropertyKey keys[] = {kNormalStiffnessKey, kTensileStrengthKey};
  static void derive(PairParams& p, const PairProperties& pair) {
    const ContactProperties& q = pair.mixed;
    p.kn = q.kn;
    p.tensile_strength = q.tensile_strength;
    p.break_separation = p.tensile_strength / p.kn;  // eq. 2.21
  }
};

// Mendes (eq. 2.22-2.25, signs as SPEC §6): linear in compression; while bonded the attraction is
// T(s) = kn [D (1 - exp(-A s)) - s], s = -u, rising to F at s* = D ln(L) / L and softening to zero
// at s0, where the bond breaks. For epsilon >= 1/e there is no tension branch: s0 = 0, the bond
// breaks once the particles separate (gap beyond kBondTouchTolerance 2R*); it carries its
// cohesion in shear until then.
struct MendesNormal {
  using Damping = ViscousDamping;
  static constexpr std::string_view keyword = "mendes";
  static constexpr bool four_wide = true;
  using WithoutBonds = CundallNormal;  // its tension needs a bond
  template <class P, class L, class M>
  [[gnu::always_inline]] static L elastic(const P& p, const L& u, const L& r_eff, M& bonded) {
    using namespace lanes;
    const M compressed = less_or_equal(L(0.0), u);
    const L s = -u;
    // A bond in tension breaks at s >= s0 (docs/physics.md P13); without tension (s0 = 0), once apart.
    const M breaks = either(both(p.mendes_tension, less_or_equal(p.break_separation, s)), but_not(separated(u, r_eff), p.mendes_tension));
    bonded = but_not(bonded, but_not(breaks, compressed));
    const M pulls = both(but_not(bonded, compressed), p.mendes_tension);
    // -T(s) of docs/physics.md P12; its exp() only on the lanes that pull, one by one with std::exp (the plain bits).
    const L tension = (-p.kn) * (p.mendes_D * (L(1.0) - exp_where(pulls, (-p.mendes_A) * s)) - s);
    return select(compressed, p.kn * u, only_where(pulls, tension));
  }
  static double stored_energy(const PairParams& p, double u, double r_eff, bool bonded) { return LiuNormal::stored_energy(p, u, r_eff, bonded); }
  // Exactly (docs/physics.md eq. P31): in tension s < s0 the work of T, kn [D (s - (1 - exp(-A s))/A) - s²/2].
  static double elastic_energy(const PairParams& p, double u, double /*r_eff*/, bool bonded) {
    if (u >= 0) return 0.5 * p.kn * u * u;
    if (!bonded || !p.mendes_tension) return 0.0;
    const double s = std::min(-u, p.break_separation);
    return p.kn * (p.mendes_D * (s - (1 - std::exp(-p.mendes_A * s)) / p.mendes_A) - 0.5 * s * s);
  }
  // The attraction starts with slope T'(0) = kn (D A - 1) = kn (L - 1), steeper than kn for
  // eps < 1/e^2 (8.2 kn at eps = 1e-4): eq. 2.48 must see it.
  static double stiffness(const PairParams& p, const ContactScale& /*scale*/) {
    return p.mendes_tension ? std::max(p.kn, p.kn * (p.mendes_D * p.mendes_A - 1)) : p.kn;
  }
  static constexpr PropertyKey keys[] = {kNormalStiffnessKey, kTensileStrengthKey, kMendesEpsilonKey};
  // The constants D, A, the zero s0 of T and whether there is tension at all (eq. 2.23-2.24).
  static void derive(PairParams& p, const PairProperties& pair);
};

// Hertz (elastic spheres, the normal part of Hertz-Mindlin; docs/contact-laws.md eq. H1-H4):
// f = 4/3 E* sqrt(R*) u^(3/2) in compression, none in tension, with the pair's effective modulus
// 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b (eq. H2) and the contact's effective radius
// 1/R* = 1/a_i + 1/a_j (a wall: R* = a_i), eq. H3. Damped by HertzDamping (eq. H6-H7).
struct HertzNormal {
  using Damping = HertzDamping;  // its dashpot grows with the contact (eq. H6)
  static constexpr std::string_view keyword = "hertz";
  static constexpr bool four_wide = true;
  using WithoutBonds = HertzNormal;
  template <class P, class L, class M>
  [[gnu::always_inline]] static L elastic(const P& p, const L& u, const L& r_eff, M& bonded) {
    break_when_apart(u, r_eff, bonded);
    return lanes::only_where(lanes::less(L(0.0), u), p.hertz_modulus * contact_radius(u, r_eff) * u);  // eq. H1, hertz_modulus = 4/3 E*
  }
  // The work of eq. H1 from first touch: 2/5 f u = 8/15 E* sqrt(R*) u^(5/2) (eq. H4).
  static double stored_energy(const PairParams& p, double u, double r_eff, bool /*bonded*/) {
    return u > 0 ? 0.4 * p.hertz_modulus * contact_radius(u, r_eff) * u * u : 0.0;
  }
  static double elastic_energy(const PairParams& p, double u, double r_eff, bool bonded) { return stored_energy(p, u, r_eff, bonded); }
  // The slope df/du = 2 E* sqrt(R* u) grows with the overlap: bounded at the largest effective
  // radius and overlap a run reaches before its overlap check stops it.
  static double stiffness(const PairParams& p, const ContactScale& scale) {
    return 1.5 * p.hertz_modulus * std::sqrt(scale.radius * scale.overlap);
  }
  static constexpr PropertyKey keys[] = {kYoungModulusKey, kPoissonRatioKey};
  static void derive(PairParams& p, const PairProperties& pair) {
    const auto compliance = [](const ContactProperties& m) { return (1 - m.poisson_ratio * m.poisson_ratio) / m.young_modulus; };
    p.hertz_modulus = 4.0 / 3.0 / (compliance(pair.a) + compliance(pair.b));  // eq. H2
    p.kn = 0;  // no linear spring
    p.break_separation = 0;
  }
};

}  // namespace dem
