#include "contact/normal_laws.hpp"

#include <cmath>

namespace dem {

void MendesNormal::derive(PairParams& p, const PairProperties& pair) {
  const ContactProperties& q = pair.mixed;
  p.kn = q.kn;
  p.tensile_strength = q.tensile_strength;
  const double epsilon = q.epsilon;
  // eq. 2.23-2.24 (SPEC §6): L = -ln eps, D = F L / (kn (L - 1 - ln L)), A = L / D. For
  // eps >= 1/e, L <= 1 and there is no tension (Cundall).
  const double L = -std::log(epsilon);
  p.mendes_tension = L > 1 && p.tensile_strength > 0;
  if (!p.mendes_tension) {
    p.mendes_D = p.mendes_A = p.break_separation = 0;
    return;
  }
  const double D = p.tensile_strength * L / (p.kn * (L - 1 - std::log(L)));
  const double A = L / D;
  p.mendes_D = D;
  p.mendes_A = A;
  // s0: the positive root of g(s) = D (1 - exp(-A s)) - s beyond the peak s* = D ln(L) / L.
  // g is concave with g(s*) > 0 and g(D) < 0, so bisection is safe; 200 halvings reach round-off.
  double lo = D * std::log(L) / L, hi = D;
  for (int k = 0; k < 200 && hi - lo > 1e-16 * D; ++k) {
    const double mid = 0.5 * (lo + hi);
    (D * (1 - std::exp(-A * mid)) - mid > 0 ? lo : hi) = mid;
  }
  p.break_separation = hi;
}

}  // namespace dem
