#pragma once
// How far particles have moved since the neighbour list was built: read every step for every
// particle, so four particles at a time with AVX2 (simd/simd.hpp) where the processor has it.
#include "core/types.hpp"
#include "state/periodic.hpp"

namespace dem {

// The largest |x - x_build|^2 of particles [first, last), through the nearest image across the
// periodic boundaries (PeriodicBox::nearest). Each particle's is (dx^2 + dy^2) + dz^2 in both
// versions (not that a last bit could matter: which steps rebuild never changes the results).
double largest_move2(const Vec3* x, const Vec3* x_build, const PeriodicBox& box, long first, long last);

}  // namespace dem
