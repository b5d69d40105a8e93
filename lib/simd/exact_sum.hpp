#pragma once
// Many terms added to an exact sum (core/fixed_sum.hpp) in one pass, four at a time where the
// four-wide loops run (simd.hpp): the same bits as adding them one by one, which cost the energy
// log's per-particle work most of its time (bench/results/design.md).
#include "core/fixed_sum.hpp"

namespace dem {

// s.add(x[k]) for each k in [0, n): the same sum, and the same term out of range where one is.
void add_all(FixedSum& s, const double* x, long n);

}  // namespace dem
