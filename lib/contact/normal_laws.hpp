#pragma once
// Elastic normal laws f_el(u_n) of SPEC §6, as small stateless types. u is the overlap (> 0 in
// compression); the result is positive when repulsive. `bonded` is the contact's bond flag Φ; a
// law clears it when the bond fails in this step (irreversible, SPEC §6 Decision).
//
// Written over a lane type (simd/lanes.hpp) where the law has a four-wide version (four_wide:
// CundallNormal); the others run one contact at a time (L = double, P = PairParams).
//
// How to add a law: write a struct with a static `elastic`, add its enum value in
// state/materials.hpp, its keyword in io/scene_parser.cpp, and a case in sim/force_loop.cpp.
#include <cmath>

#include "simd/lanes.hpp"
#include "state/materials.hpp"

namespace dem {

// Cundall & Strack: linear in compression, no tension.
struct CundallNormal {
  static constexpr bool four_wide = true;
  template <class P, class L, class M>
  [[gnu::always_inline]] static L elastic(const P& p, const L& u, M& /*bonded*/) {
    return lanes::only_where(lanes::less(L(0.0), u), p.kn * u);
  }
};

// Liu (eq. 2.21): linear in compression and, while bonded, in tension up to the strength F; the
// bond breaks abruptly when the tension would exceed F.
struct LiuNormal {
  static constexpr bool four_wide = false;
  static double elastic(const PairParams& p, double u, bool& bonded) {
    if (u >= 0) return p.kn * u;
    if (!bonded) return 0.0;
    if (-p.kn * u > p.tensile_strength) {
      bonded = false;
      return 0.0;
    }
    return p.kn * u;
  }
};

// Mendes (eq. 2.22-2.25, signs as SPEC §6): linear in compression; while bonded the attraction is
// T(s) = kn [D (1 - exp(-A s)) - s], s = -u, rising to F at s* = D ln(L) / L and softening to zero
// at s0, where the bond breaks.
struct MendesNormal {
  static constexpr bool four_wide = false;
  static double elastic(const PairParams& p, double u, bool& bonded) {
    if (u >= 0) return p.kn * u;
    if (!bonded || !p.mendes_tension) return 0.0;
    const double s = -u;
    if (s >= p.break_separation) {
      bonded = false;
      return 0.0;
    }
    return -p.kn * (p.mendes_D * (1 - std::exp(-p.mendes_A * s)) - s);
  }
};

// A scene whose material pairs use different laws: choose per contact.
struct MixedNormal {
  static constexpr bool four_wide = false;
  static double elastic(const PairParams& p, double u, bool& bonded) {
    switch (p.law) {
      case NormalLaw::Liu: return LiuNormal::elastic(p, u, bonded);
      case NormalLaw::Mendes: return MendesNormal::elastic(p, u, bonded);
      case NormalLaw::Cundall: break;
    }
    return CundallNormal::elastic(p, u, bonded);
  }
};

}  // namespace dem
