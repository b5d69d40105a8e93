#pragma once
// How far particles have moved since the neighbour list was built: read every step for every
// particle, so four particles at a time with AVX2 (simd/simd.hpp) where the processor has it.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/types.hpp"
#include "state/periodic.hpp"

namespace dem {

// The displacements d = x - x_build of some particles, through the nearest image across the
// periodic boundaries (PeriodicBox::nearest): the largest |d|^2, each (dx^2 + dy^2) + dz^2, and the
// box [lo, hi] holding every d. (Not that a last bit could matter: which steps rebuild never
// changes the results.)
struct Moves {
  double largest2 = 0;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void add(const Moves& o) { largest2 = std::max(largest2, o.largest2), lo = lo.cwiseMin(o.lo), hi = hi.cwiseMax(o.hi); }
  // How much closer any two of the particles can have come (docs/physics.md eq. P85): at most
  // twice the largest move, and at most the diagonal of the box of the moves, since for its
  // centre c, |d_a - d_b| <= |d_a - c| + |d_b - c|. The second is the smaller where the particles
  // moved together (a free fall, a flow); none moved, or no particles: 0.
  double approach() const { return std::min(2 * std::sqrt(largest2), (hi - lo).norm()); }
};

// The moves of particles [first, last).
Moves moves_since(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last);

}  // namespace dem
