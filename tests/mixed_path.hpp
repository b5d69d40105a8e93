#pragma once
// Material `m` beside a second one of another normal law that no particle uses: the force loop then
// takes the per-contact ("mixed") path of lib/forces/block_forces.hpp for every contact, which must
// give the physics the compiled path gives.
#include <gtest/gtest.h>

#include "forces/force_loop.hpp"
#include "state/materials.hpp"

namespace dem {

inline MaterialTable on_the_mixed_path(const Material& m) {
  Material other = m;
  other.name = m.name + "-unused";
  other.law = m.law == NormalLaw::Hertz ? NormalLaw::Cundall : NormalLaw::Hertz;
  if (other.kn <= 0) other.kn = other.kt = 1e5;
  if (other.young_modulus <= 0) other.young_modulus = 1e8, other.poisson_ratio = 0.3;
  PairOverride between;
  between.a = 0, between.b = 1;
  between.law = m.law, between.tangential = m.tangential, between.rolling = m.rolling;
  MaterialTable t({m, other}, {}, {between});
  EXPECT_EQ(variant_name(choose_force_variant(t, false)), "mixed");
  return t;
}

inline MaterialTable alone_or_on_the_mixed_path(const Material& m, bool mixed) {
  return mixed ? on_the_mixed_path(m) : MaterialTable({m}, {});
}

}  // namespace dem
